#include "report/report_markdown.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "report/testdata/synthetic_report.h"
#include "tests/scratch_dir.h"

namespace twinrender::report {
namespace {

using namespace twinrender::compare;  // what the report shows

namespace fs = std::filesystem;
using testdata::sceneWithChecks;

// planet (fails two metrics, warns on one), contact (passes), a scene that could not be
// rendered, with a name and an error that Markdown would otherwise take as markup.
RunReport threeScenes(bool withBaseline) {
    RunReport run;
    run.createdAt = "2024-01-01 00:00 UTC";
    run.commandLine = "twinrender run scenes";
    run.thresholdsFile = "scenes/thresholds.toml";
    if (withBaseline) run.baselineFile = "baseline.json";
    run.scenes.push_back(sceneWithChecks());
    if (!withBaseline) run.scenes.back().checks.pop_back();  // the baseline check
    SceneReport ok;
    ok.name = "contact";
    ok.metrics = {{"beauty.flip", 0.05}};
    run.scenes.push_back(ok);
    SceneReport broken;
    broken.name = "ring|world";
    broken.error = "no *GL*\nat all";
    run.scenes.push_back(broken);
    return run;
}

TEST(ReportMarkdown, VerdictAndOneRowPerSceneWithWhatFailedOrWarned) {
    const std::string md = summaryMarkdown(threeScenes(true));
    const std::string expected =
        "## twinrender: ❌ fail\n"
        "\n"
        "3 scenes: 2 fail, 1 pass. Thresholds: scenes/thresholds.toml. Baseline: baseline.json. "
        "[The report](index.html) has every metric, image and error map.\n"
        "\n"
        "| Scene | Status | Failed or warned | Value | Bound crossed | Change from baseline |\n"
        "| --- | --- | --- | ---: | --- | ---: |\n"
        "| [planet](planet/index.html) | ❌ fail | "
        "[beauty.flip](planet/index.html#metric-beauty.flip)<br>"
        "[coverage.iou](planet/index.html#metric-coverage.iou)<br>"
        "[shadow.iou](planet/index.html#metric-shadow.iou) (warn) | "
        "0.2<br>not computed<br>0.97 | "
        "max 0.15; baseline 0.1, worst allowed 0.102<br>min 0.9<br>warn\\_min 0.98 | "
        "+0.1 (+100.0 %)<br>—<br>— |\n"
        "| [contact](contact/index.html) | ✅ pass |  |  |  |  |\n"
        "| [ring\\|world](ring%7Cworld/index.html) | ❌ fail | could not be rendered or compared: "
        "no \\*GL\\* at all |  |  |  |\n";
    EXPECT_EQ(md, expected) << md;
}

TEST(ReportMarkdown, NoChangeColumnWithoutABaseline) {
    const std::string md = summaryMarkdown(threeScenes(false));
    EXPECT_EQ(md.find("Change from baseline"), std::string::npos) << md;
    EXPECT_EQ(md.find("Baseline:"), std::string::npos) << md;
    EXPECT_NE(md.find("| 0.2<br>not computed<br>0.97 | max 0.15<br>min 0.9<br>warn\\_min 0.98 |\n"),
              std::string::npos)
        << md;
    // Every row of the table has as many cells as its header: 6 unescaped '|'.
    std::istringstream lines(md);
    std::string line;
    while (std::getline(lines, line)) {
        if (line.rfind("| ", 0) != 0) continue;
        int bars = 0;
        for (std::size_t i = 0; i < line.size(); ++i)
            bars += line[i] == '|' && (i == 0 || line[i - 1] != '\\');
        EXPECT_EQ(bars, 6) << line;
    }
}

TEST(ReportMarkdown, AFailedMetricShowsTheBoundItFailedNotItsWarning) {
    RunReport run;
    SceneReport s;
    s.name = "planet";
    s.metrics = {{"beauty.flip", 0.2}};
    s.checks = evaluate(
        s.metrics,
        Thresholds::parseString("\"beauty.flip\" = { max = 0.15, warn_max = 0.1 }\n", "t.toml")
            .global());
    run.scenes.push_back(s);
    const std::string md = summaryMarkdown(run);
    EXPECT_NE(md.find("| 0.2 | max 0.15 |\n"), std::string::npos) << md;
    EXPECT_EQ(md.find("warn\\_max"), std::string::npos) << md;
}

TEST(ReportMarkdown, APassingRunAndAnEmptyOne) {
    RunReport run;
    EXPECT_EQ(summaryMarkdown(run),
              "## twinrender: ✅ pass\n\n0 scenes. No thresholds file. [The report](index.html) "
              "has every metric, image and error map.\n\n");
    SceneReport ok;
    ok.name = "planet";
    run.scenes.push_back(ok);
    EXPECT_NE(summaryMarkdown(run).find("1 scene: 1 pass."), std::string::npos);
}

TEST(ReportMarkdown, WrittenWithTheReport) {
    const fs::path dir = twinrender::testing::freshDir("report_markdown");
    const RunReport run = testdata::syntheticReport(dir);
    writeReport(run, dir);
    std::ifstream in(dir / "summary.md");
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), summaryMarkdown(run));
    // Every scene page a row links to exists, with the metric's row.
    for (const SceneReport& s : run.scenes) {
        EXPECT_NE(text.str().find("](" + s.name + "/index.html)"), std::string::npos) << s.name;
        EXPECT_TRUE(fs::exists(dir / s.name / "index.html")) << s.name;
    }
    std::ifstream page(dir / "sphere_shifted" / "index.html");
    std::stringstream html;
    html << page.rdbuf();
    EXPECT_NE(html.str().find("<tr id=\"metric-shadow.iou\">"), std::string::npos);
    EXPECT_NE(text.str().find("(sphere_shifted/index.html#metric-shadow.iou)"), std::string::npos)
        << text.str();
}

}  // namespace
}  // namespace twinrender::report
