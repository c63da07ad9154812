#include "report/index_page.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "report/report_html.h"
#include "report/scene_facts.h"
#include "report/testdata/read_text.h"
#include "report/testdata/synthetic_report.h"
#include "tests/scratch_dir.h"

namespace twinrender::report {
namespace {

namespace fs = std::filesystem;

using testdata::readText;

// A sequence of three frames whose header frame is not the median one.
SceneReport sequenceScene() {
    SceneReport s;
    s.name = "collision";
    s.renderers["realtime"].timingsMs = {{"total", 124.4}, {"shade", 10.0}, {"ao", 0.0}};
    s.renderers["realtime"].device = "llvmpipe (LLVM 15.0.6, 256 bits)";
    s.renderers["raymarch"].timingsMs = {{"total", 3000.0}};
    s.metrics = {{"beauty.flip", 0.03}, {"time.realtime_ms", 136.5}, {"time.raymarch_ms", 2900.0}};
    SequenceReport q;
    q.frames = {{.frame = 12, .metrics = {{"time.realtime_ms", 140.0}}, .notApplicable = {}},
                {.frame = 13, .metrics = {{"time.realtime_ms", 124.4}}, .notApplicable = {}},
                {.frame = 14, .metrics = {{"time.realtime_ms", 136.5}}, .notApplicable = {}}};
    q.shownFrame = 13;
    s.sequence = q;
    return s;
}

TEST(SceneFacts, OneTimePerSceneTheMedianForASequence) {
    const SceneReport s = sequenceScene();
    EXPECT_DOUBLE_EQ(*sceneTimeMs(s, "realtime"), 136.5);  // not frame 13's 124.4
    EXPECT_EQ(timeBasis(s), "median of 3 frames");
    EXPECT_EQ(speedRatio(s), "21.2×");  // 2900 / 136.5
    SceneReport still;
    still.renderers["realtime"].timingsMs = {{"total", 4.0}};
    EXPECT_DOUBLE_EQ(*sceneTimeMs(still, "realtime"), 4.0);
    EXPECT_EQ(timeBasis(still), "");
    EXPECT_FALSE(sceneTimeMs(still, "raymarch"));
}

TEST(SceneFacts, AnExternalRendererIsNamedByItsProgram) {
    SceneReport s;
    s.renderers["external"].device = "external: /usr/bin/python3 -u examples/vtk_fluid/render.py";
    s.renderers["raymarch"];
    EXPECT_EQ(testRenderer(s), "external");
    EXPECT_EQ(rendererLabel(s, "external"), "External: render.py");
    s.renderers["external"].device = "external: /opt/bin/myrender --fast";
    EXPECT_EQ(rendererLabel(s, "external"), "External: myrender");
    s.renderers["external"].device = "";
    EXPECT_EQ(rendererLabel(s, "external"), "External renderer");
    RunReport run;
    run.scenes = {s};
    EXPECT_EQ(runTestLabel(run), "External renderer");
}

TEST(IndexPage, TheHeadlineTableTheDeviceAndEveryMetricAClickAway) {
    const fs::path dir = twinrender::testing::freshDir("report_index_page");
    RunReport run = testdata::syntheticReport(dir);
    run.scenes.push_back(sequenceScene());
    const std::string index = indexPage(run);
    // The headline table: verdict, the headline metrics, the error split, the times.
    const std::size_t table = index.find("<table class=\"scenes\" id=\"scenes\" data-fit>");
    const std::size_t tableEnd = index.find("</table>", table);
    ASSERT_NE(table, std::string::npos);
    const std::string headline = index.substr(table, tableEnd - table);
    for (const char* m : INDEX_HEADLINE)
        EXPECT_NE(headline.find(std::string(">") + m + "<"), std::string::npos) << m;
    EXPECT_EQ(headline.find(">beauty.psnr<"), std::string::npos);  // in the full table only
    EXPECT_NE(headline.find("Error from</th>"), std::string::npos);
    EXPECT_NE(headline.find("class=\"split compact\""), std::string::npos);
    EXPECT_NE(headline.find("<th class=\"num\">Real-time <span"), std::string::npos);
    // The sequence's time is its median, with what it is in the tooltip.
    EXPECT_NE(headline.find("title=\"median of 3 frames\">136.5 ms</td>"), std::string::npos);
    // Every overview metric a click away, under a sticky scene column and a hint.
    EXPECT_NE(index.find("<details class=\"all-metrics\">"), std::string::npos);
    EXPECT_NE(index.find(">beauty.psnr<", tableEnd), std::string::npos);
    EXPECT_NE(index.find("Scroll sideways"), std::string::npos);
    EXPECT_NE(index.find("<td class=\"sticky\">"), std::string::npos);
    // The device, and what a software rasteriser means for the times.
    EXPECT_NE(index.find("Real-time on <b class=\"device\">llvmpipe (LLVM 15.0.6, 256 bits)"),
              std::string::npos);
    EXPECT_NE(index.find("a software rasteriser"), std::string::npos);
    // A value without a bound says where a bound would go.
    EXPECT_NE(index.find("no bound: thresholds.toml sets none"), std::string::npos);
}

TEST(IndexPage, AnExternalRenderersColumnAndSwapViewNameIt) {
    const fs::path dir = twinrender::testing::freshDir("report_index_external");
    RunReport run = testdata::syntheticReport(dir);
    for (SceneReport& s : run.scenes) {
        s.renderers["external"] = s.renderers.at("realtime");
        s.renderers["external"].device = "external: python3 render.py";
        s.renderers.erase("realtime");
    }
    writeHtmlReport(run, dir);
    const std::string index = readText(dir / "index.html");
    EXPECT_NE(index.find("<th class=\"num\">External: render.py <span"), std::string::npos);
    EXPECT_EQ(index.find(">Real-time"), std::string::npos);
    EXPECT_EQ(index.find("software rasteriser"), std::string::npos);
    const std::string scene = readText(dir / "sphere" / "index.html");
    EXPECT_NE(scene.find("<span class=\"tag left\">External: render.py</span>"), std::string::npos);
    EXPECT_EQ(scene.find(">Real-time<"), std::string::npos);
}

TEST(ScenePage, NotApplicableStagesNotRunNeighboursFilesAndTheSplit) {
    const fs::path dir = twinrender::testing::freshDir("report_scene_page");
    RunReport run = testdata::syntheticReport(dir);
    SceneReport& s = run.scenes[0];
    s.errorMaps["shadow"] = {"flip.png", "shadow: 1 false, 2 missed", 0.0, 2.0, ""};
    writeReport(run, dir);
    const std::string page = readText(dir / "sphere" / "index.html");
    // emission.rmse does not apply: n/a with the reason, never 0.
    EXPECT_NE(page.find("title=\"not applicable: neither render has any emission\">n/a</td>"),
              std::string::npos);
    EXPECT_NE(page.find(">not applicable</span>"), std::string::npos);
    // The ao stage did not run: left out, and said so.
    EXPECT_EQ(page.find("<tr><td>ao</td>"), std::string::npos);
    EXPECT_NE(page.find("Not run for this scene, so left out: ao."), std::string::npos);
    // The device in the header, and the software rasteriser's note.
    EXPECT_NE(page.find("Real-time 2.5 ms on <b class=\"device\">llvmpipe"), std::string::npos);
    EXPECT_NE(page.find("class=\"device-note\""), std::string::npos);
    // Next scene, the way back, the raw files.
    EXPECT_NE(page.find("<a rel=\"next\" href=\"../sphere_shifted/index.html\">"),
              std::string::npos);
    EXPECT_EQ(page.find("rel=\"prev\""), std::string::npos);
    for (const char* f : {"realtime.exr", "raymarch.exr", "realtime.json", "metrics.json"})
        EXPECT_NE(page.find(fmt::format("<a href=\"{0}\">{0}</a>", f)), std::string::npos) << f;
    // The error split as bars: the whole and its three parts.
    EXPECT_NE(page.find("<section id=\"error-split\">"), std::string::npos);
    for (const char* part : {"whole", "surface", "lighting", "shading"})
        EXPECT_NE(page.find(std::string("class=\"split-row ") + part + "\""), std::string::npos)
            << part;
    // The shadow map's legend: three cases, not a colour bar.
    EXPECT_NE(page.find("<div class=\"categories\">"), std::string::npos);
    for (const char* c : {"agree (or no surface)", "false shadow", "missed shadow"})
        EXPECT_NE(page.find(c), std::string::npos) << c;
    const std::string shifted = readText(dir / "sphere_shifted" / "index.html");
    EXPECT_NE(shifted.find("<a rel=\"prev\" href=\"../sphere/index.html\">"), std::string::npos);
}

}  // namespace
}  // namespace twinrender::report
