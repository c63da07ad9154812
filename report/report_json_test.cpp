#include "report/report_json.h"

#include <gtest/gtest.h>

#include <cmath>

#include "compare/json_number.h"
#include "report/testdata/synthetic_report.h"

namespace twinrender::report {
namespace {

using namespace twinrender::compare;  // what the report shows

using nlohmann::json;
using testdata::sceneWithChecks;

TEST(ReportJson, MetricsJsonHasTheDesignedShape) {
    const SceneReport s = sceneWithChecks();
    const json j = json::parse(metricsJson(s).dump());
    EXPECT_EQ(j["scene"], "planet");
    EXPECT_EQ(j["status"], "fail");
    EXPECT_EQ(j["metrics"]["beauty.flip"], 0.2);
    EXPECT_EQ(j["metrics"]["beauty.psnr"], "Infinity");  // JSON has no infinity
    ASSERT_TRUE(j["checks"].is_array());
    ASSERT_EQ(j["checks"].size(),
              5u);  // flip max, coverage min (missing), iou min, warn_min, baseline
    for (const auto& c : j["checks"]) {
        for (const char* key : {"metric", "value", "bound", "status", "message"})
            EXPECT_TRUE(c.contains(key)) << key << " in " << c.dump();
    }
    EXPECT_EQ(j["checks"][0]["metric"], "beauty.flip");
    EXPECT_EQ(j["checks"][0]["bound"], "max");
    EXPECT_EQ(j["checks"][0]["status"], "fail");
    EXPECT_EQ(j["checks"][1]["metric"], "coverage.iou");
    EXPECT_EQ(j["checks"][1]["value"], "NaN");
    EXPECT_EQ(j["checks"][3]["status"], "warn");
    EXPECT_EQ(j["checks"][4]["bound"], "baseline");
    EXPECT_EQ(j["checks"][4]["baseline"], 0.1);
    EXPECT_NEAR(j["checks"][4]["delta"].get<double>(), 0.1, 1e-12);
    EXPECT_EQ(j["timings_ms"]["realtime"]["ssss"], 1.5);
    EXPECT_TRUE(j["error_maps"].is_object());
    EXPECT_EQ(numberFromJson(j["metrics"]["beauty.psnr"]), std::numeric_limits<double>::infinity());
    EXPECT_TRUE(std::isnan(*numberFromJson(j["checks"][1]["value"])));
    EXPECT_FALSE(numberFromJson(json("text")));
}

TEST(ReportJson, SummaryJsonHasTheDesignedShape) {
    RunReport run;
    run.scenes.push_back(sceneWithChecks());
    SceneReport ok;
    ok.name = "contact";
    ok.metrics = {{"beauty.flip", 0.01}};
    run.scenes.push_back(ok);
    SceneReport broken;
    broken.name = "ringworld";
    broken.error = "ringworld.toml:3:1: unknown key 'x'";
    run.scenes.push_back(broken);
    const json j = json::parse(summaryJson(run).dump());
    EXPECT_EQ(j["status"], "fail");
    ASSERT_EQ(j["scenes"].size(), 3u);
    EXPECT_EQ(j["scenes"][0]["name"], "planet");
    EXPECT_EQ(j["scenes"][0]["status"], "fail");
    EXPECT_EQ(j["scenes"][0]["timings_ms"]["raymarch"]["total"], 400.0);
    EXPECT_EQ(j["scenes"][1]["status"], "pass");
    EXPECT_EQ(j["scenes"][1]["metrics"]["beauty.flip"], 0.01);
    EXPECT_EQ(j["scenes"][2]["status"], "fail");
    EXPECT_EQ(j["scenes"][2]["error"], broken.error);
    // A summary is what bless reads.
    const Baseline b = bless(j, "summary.json");
    EXPECT_EQ(b.scenes.at("contact").metrics.at("beauty.flip"), 0.01);
}

TEST(SceneReportJson, RoundTripsEveryField) {
    SceneReport s;
    s.name = "planet";
    s.description = "d";
    s.metrics = {{"beauty.flip", 0.1}, {"beauty.psnr", INFINITY}};
    s.baseline = {{"beauty.flip", 0.09}};
    Check c;
    c.metric = "beauty.flip";
    c.value = 0.1;
    c.bound = "baseline";
    c.limit = 0.095;
    c.status = Status::Fail;
    c.message = "worse";
    c.where = "b.json";
    c.baseline = 0.09;
    s.checks = {c};
    s.renderers["realtime"] = {{{"total", 3.0}},
                               "llvmpipe",
                               {{"particles_drawn", 5}},
                               {{"beauty", "realtime.beauty.png"}}};
    s.errorMaps["beauty"] = {"error.beauty.png", "ꟻLIP error", 0, 1, ""};
    s.settings = {{"scene_file", "x.toml"}};
    const auto j = sceneReportJson(s);
    const SceneReport back = sceneReportFromJson(nlohmann::json::parse(j.dump()), "x");
    EXPECT_EQ(sceneReportJson(back), j);
    EXPECT_EQ(metricsJson(back), metricsJson(s));
    EXPECT_EQ(back.renderers.at("realtime").images.at("beauty"), "realtime.beauty.png");
    EXPECT_EQ(back.status(), Status::Fail);

    // A sequence scene's frames, video and charts too.
    SequenceReport q;
    q.fps = 5.0;
    q.frames = {{16, {{"beauty.flip", 0.05}}, {{"ao.mean_abs", "no occlusion"}}},
                {17, {{"temporal.flicker", -0.01}}, {}}};
    q.shownFrame = 16;
    q.videos = {{"video/webm", "sequence.webm"}};
    q.charts = {{"beauty.flip", "charts/beauty.flip.svg"}};
    s.sequence = q;
    const auto js = sceneReportJson(s);
    const SceneReport seq = sceneReportFromJson(nlohmann::json::parse(js.dump()), "x");
    EXPECT_EQ(sceneReportJson(seq), js);
    ASSERT_TRUE(seq.sequence);
    EXPECT_EQ(seq.sequence->frames.at(1).frame, 17);
    EXPECT_EQ(seq.sequence->frames.at(0).notApplicable.at("ao.mean_abs"), "no occlusion");
    EXPECT_EQ(metricsJson(s)["sequence"]["frames"].size(), 2u);

    // Several test renderers side by side: each one's results, for `merge` to show them again.
    TestRendererReport external;
    external.name = "external";
    external.metrics = {{"beauty.flip", 0.2}};
    external.notProvided = {"shadow.iou"};
    external.render.timingsMs = {{"total", 9.0}};
    external.render.device = "external: mine";
    external.render.images = {{"beauty", "tests/external/external.beauty.png"}};
    TestRendererReport own;
    own.name = "realtime";
    own.metrics = s.metrics;
    own.checks = {c};
    s.tests = {own, external};
    const auto jt = sceneReportJson(s);
    const SceneReport tests = sceneReportFromJson(nlohmann::json::parse(jt.dump()), "x");
    EXPECT_EQ(sceneReportJson(tests), jt);
    ASSERT_EQ(tests.tests.size(), 2u);
    EXPECT_EQ(tests.tests[1].notProvided, std::vector<std::string>{"shadow.iou"});
    EXPECT_EQ(tests.tests[1].render.images.at("beauty"), "tests/external/external.beauty.png");
}

}  // namespace
}  // namespace twinrender::report
