#include "report/annotations.h"

#include <gtest/gtest.h>

#include "report/testdata/synthetic_report.h"

namespace twinrender::report {
namespace {

using namespace twinrender::compare;  // what the report shows

namespace fs = std::filesystem;

TEST(GithubAnnotations, EscapesAsGithubsToolkitDoes) {
    EXPECT_EQ(escapeWorkflowData("50% a:b, c\r\nd"), "50%25 a:b, c%0D%0Ad");
    EXPECT_EQ(escapeWorkflowProperty("50% a:b, c\r\nd"), "50%25 a%3Ab%2C c%0D%0Ad");
}

TEST(GithubAnnotations, OneLinePerCheckThatDidNotPassNamingTheSceneFile) {
    RunReport run;
    run.scenes.push_back(testdata::sceneWithChecks());
    run.scenes.back().settings = {{"scene_file", "/repo/scenes/planet.toml"}};
    SceneReport ok;
    ok.name = "contact";
    ok.settings = {{"scene_file", "/repo/scenes/contact.toml"}};
    run.scenes.push_back(ok);
    SceneReport broken;
    broken.name = "ring,world";
    broken.settings = {{"scene_file", "/elsewhere/ring.toml"}};
    broken.error = "no GL: 50%\nof nothing";
    run.scenes.push_back(broken);
    EXPECT_EQ(githubAnnotations(run, "/repo"),
              "::error file=scenes/planet.toml,title=twinrender planet%3A beauty.flip "
              "failed::beauty.flip = 0.2 is above its max 0.15 (t.toml:1:25)\n"
              "::error file=scenes/planet.toml,title=twinrender planet%3A coverage.iou "
              "failed::coverage.iou was not computed, but its min 0.9 (t.toml:3:26) is set; check "
              "the metric's name, or that both renders have the buffers it needs\n"
              "::warning file=scenes/planet.toml,title=twinrender planet%3A shadow.iou "
              "warned::shadow.iou = 0.97 is below its warn_min 0.98 (t.toml:2:40)\n"
              "::error file=scenes/planet.toml,title=twinrender planet%3A beauty.flip "
              "failed::beauty.flip got worse than the baseline: 0.1 -> 0.2 (delta +0.1, +100.0 "
              "%25); the tolerance allows 0.002 (2 %25 of 0.1, at least 0.001)\n"
              "::error file=/elsewhere/ring.toml,title=twinrender ring%2Cworld%3A not rendered "
              "or compared::no GL: 50%25%0Aof nothing\n");
    // Outside the root, and without a root, the file as the report has it.
    EXPECT_EQ(githubAnnotations(run, "").rfind("::error file=/repo/scenes/planet.toml,", 0), 0u);
    RunReport passing;
    passing.scenes.push_back(ok);
    EXPECT_EQ(githubAnnotations(passing, "/repo"), "");
}

TEST(GithubAnnotations, AFailedMetricIsOneErrorWithoutItsWarning) {
    SceneReport s;
    s.name = "planet";
    s.metrics = {{"beauty.flip", 0.2}, {"beauty.ssim", 0.8}};
    s.checks = evaluate(s.metrics, Thresholds::parseString("\"beauty.flip\" = { max = 0.15, "
                                                           "warn_max = 0.1 }\n\"beauty.ssim\" = { "
                                                           "warn_min = 0.9 }\n",
                                                           "t.toml")
                                       .global());
    RunReport run;
    run.scenes.push_back(s);
    const std::string lines = githubAnnotations(run, "");
    EXPECT_EQ(lines,
              "::error title=twinrender planet%3A beauty.flip failed::beauty.flip = 0.2 is above "
              "its max 0.15 (t.toml:1:25)\n"
              "::warning title=twinrender planet%3A beauty.ssim warned::beauty.ssim = 0.8 is below "
              "its warn_min 0.9 (t.toml:2:30)\n");
}

TEST(GithubAnnotations, ABoundOfTheSceneFileGivesItsLine) {
    SceneReport s;
    s.name = "planet";
    s.settings = {{"scene_file", "scenes/planet.toml"}};
    s.metrics = {{"shadow.iou", 0.5}};
    MetricBounds b;
    b.min = Limit{0.9, "scenes/planet.toml:41:14"};
    s.checks = evaluate(s.metrics, {{"shadow.iou", b}});
    RunReport run;
    run.scenes.push_back(s);
    const std::string lines = githubAnnotations(run, fs::current_path());
    EXPECT_EQ(lines.rfind("::error file=scenes/planet.toml,line=41,title=", 0), 0u) << lines;
}

}  // namespace
}  // namespace twinrender::report
