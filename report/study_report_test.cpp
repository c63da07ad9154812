#include "report/study_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "report/markup.h"
#include "report/published_findings.h"
#include "report/testdata/read_text.h"
#include "report/testdata/xml_check.h"
#include "tests/scratch_dir.h"

namespace tc = twinrender::report;
namespace fs = std::filesystem;

namespace {

tc::StudyResult twoRows() {
    tc::StudyResult s;
    s.name = "depth_range";
    s.title = "Depth <range>";
    s.question = "Where does it break?";
    s.sceneFile = "scenes/studies/depth_range.toml";
    s.xLabel = "far / near";
    s.xLog = true;
    s.metric = "occlusion.error";
    s.columns = {"occlusion.error", "id.mismatch"};
    s.finding = "standard depth breaks from far/near 1e6";
    s.facts = {{"breaks_at", 1e6}};
    s.unbracketedRays = 3;
    s.references = 2;
    tc::StudyRow a;
    a.series = "standard depth";
    a.x = 100;
    a.sets = {"camera.far=100", "realtime.depth=\"standard\""};
    a.metrics = {{"occlusion.error", 0.01}, {"id.mismatch", NAN}, {"count.unbracketed_rays", 1}};
    a.timingsMs = {{"total", 2.5}, {"ssss", 0.5}};
    a.referenceMs = 30;
    a.images = {{"realtime", "points/000.realtime.png"}};
    tc::StudyRow b = a;
    b.x = 1e6;
    b.metrics["occlusion.error"] = 1.0;
    b.error = "lost, \"all\"";
    s.rows = {a, b};
    s.chart.series = {{"standard depth", {{100, 0.01, ""}, {1e6, 1.0, ""}}, false}};
    return s;
}

using tc::testdata::readText;

}  // namespace

TEST(StudyReport, CsvOneLinePerRowStudyColumnsFirst) {
    const std::string csv = tc::studyCsv(twoRows());
    std::istringstream in(csv);
    std::string header, first, second;
    std::getline(in, header);
    std::getline(in, first);
    std::getline(in, second);
    EXPECT_EQ(header,
              "series,x,sets,time.total_ms,time.ssss_ms,reference_ms,occlusion.error,id.mismatch,"
              "count.unbracketed_rays,error");
    EXPECT_EQ(
        first,
        "standard "
        "depth,100,\"camera.far=100;realtime.depth=\"\"standard\"\"\",2.5,0.5,30,0.01,nan,1,");
    const std::string error = ",\"lost, \"\"all\"\"\"";  // CSV-quoted, last column
    ASSERT_GE(second.size(), error.size());
    EXPECT_EQ(second.substr(second.size() - error.size()), error);
}

TEST(StudyReport, JsonKeepsFindingFactsAndNonFiniteValues) {
    const auto j = tc::studyJson(twoRows());
    EXPECT_EQ(j["format"], "twinrender-study");
    EXPECT_EQ(j["finding"], "standard depth breaks from far/near 1e6");
    EXPECT_EQ(j["facts"]["breaks_at"], 1e6);
    EXPECT_EQ(j["unbracketed_rays"], 3.0);
    ASSERT_EQ(j["rows"].size(), 2u);
    EXPECT_EQ(j["rows"][0]["metrics"]["id.mismatch"], "NaN");
    EXPECT_EQ(j["rows"][1]["error"], "lost, \"all\"");
    EXPECT_FALSE(j["rows"][0].contains("error"));
}

TEST(StudyReport, FilesAndThePageOfAllStudies) {
    const fs::path dir = twinrender::testing::freshDir("study_report_test");
    const tc::StudyResult s = twoRows();
    tc::writeStudy(s, dir);
    tc::writeStudiesIndex({s}, dir, "2026-01-01 00:00 UTC", "twinrender study depth_range");
    for (const char* f : {"depth_range/study.json", "depth_range/study.csv",
                          "depth_range/study.svg", "studies.json", "index.html"})
        EXPECT_TRUE(fs::exists(dir / f)) << f;
    EXPECT_EQ(twinrender::test::checkXml(readText(dir / "depth_range/study.svg")).error, "");
    const std::string html = readText(dir / "index.html");
    EXPECT_NE(html.find("Depth &lt;range&gt;"), std::string::npos);
    EXPECT_NE(html.find("standard depth breaks from far/near 1e6"), std::string::npos);
    EXPECT_NE(html.find("<img src=\"depth_range/study.svg\""), std::string::npos);
    EXPECT_NE(html.find("depth_range/points/000.realtime.png"), std::string::npos);
    EXPECT_NE(html.find("id=\"selftest\""), std::string::npos);
    // A full run under no report: no quick label, no way back.
    EXPECT_EQ(html.find("quick run"), std::string::npos);
    EXPECT_EQ(html.find("← Report"), std::string::npos);
    fs::remove_all(dir);
}

TEST(StudyReport, AQuickRunSaysSoBesideEachFindingAndLinksBackToItsReport) {
    const fs::path dir = twinrender::testing::freshDir("study_report_quick");
    const tc::StudyResult s = twoRows();
    tc::writeStudy(s, dir);
    tc::writeStudiesIndex({s}, dir, "", "twinrender run --studies quick", true, "../index.html");
    const std::string html = readText(dir / "index.html");
    EXPECT_NE(html.find("<a class=\"back\" href=\"../index.html\">← Report</a>"),
              std::string::npos);
    // In the findings' table and under the study's heading, each followed by the published
    // finding of the full study and the docs page that holds it (docs/findings.json).
    const auto published = tc::publishedFinding("depth_range");
    ASSERT_TRUE(published);
    const std::string after = "</span> standard depth breaks from far/near 1e6";
    std::size_t labels = 0;
    for (auto at = html.find(">quick run" + after); at != std::string::npos;
         at = html.find(">quick run" + after, at + 1)) {
        ++labels;
        const auto next = html.find("<b>Published</b> (full run", at);
        ASSERT_NE(next, std::string::npos);
        EXPECT_LT(next - at, 400u) << "the published finding follows the quick one";
        EXPECT_EQ(
            html.compare(html.find("<code>", next) + 6, published->page.size(), published->page),
            0);
    }
    EXPECT_EQ(labels, 2u);
    std::size_t shown = 0;
    for (auto at = html.find(tc::htmlEscape(published->finding)); at != std::string::npos;
         at = html.find(tc::htmlEscape(published->finding), at + 1))
        ++shown;
    EXPECT_EQ(shown, 2u);
    fs::remove_all(dir);
}

TEST(StudyReport, PublishedFindingsAreShownForQuickRunsOnly) {
    // The compiled-in docs/findings.json publishes depth_range, not a study it does not know.
    EXPECT_TRUE(tc::publishedFinding("depth_range"));
    EXPECT_FALSE(tc::publishedFinding("no_such_study"));
    const fs::path dir = twinrender::testing::freshDir("study_report_published");
    tc::StudyResult s = twoRows();
    tc::writeStudiesIndex({s}, dir, "", "twinrender study depth_range");
    EXPECT_EQ(readText(dir / "index.html").find("<b>Published</b>"), std::string::npos);
    s.name = "no_such_study";
    tc::writeStudiesIndex({s}, dir, "", "twinrender run --studies quick", true);
    const std::string html = readText(dir / "index.html");
    EXPECT_NE(html.find(">quick run</span>"), std::string::npos);
    EXPECT_EQ(html.find("<b>Published</b>"), std::string::npos);
    fs::remove_all(dir);
}

namespace {

// A study whose points span two scenes, with a scatter chart, a figure and a table.
tc::StudyResult acrossScenes() {
    tc::StudyResult s = twoRows();
    s.name = "methods";
    s.title = "Surface methods";
    s.columns = {"normal.mean_deg"};
    s.rows[0].scene = "planet";
    s.rows[1].scene = "splash_sheet";
    s.rows[1].error.clear();
    s.scatter = tc::ScatterChart{};
    s.scatter->title = "time against normal error";
    s.scatter->points = {{2.0, 1.5, "none"}, {3.0, 1.2, "ssss 0.6"}};
    s.scatter->groups = {"none, sphere", "ssss, sphere"};
    s.figures.push_back({"particle_size", "Normal error against particle size.", s.chart});
    tc::StudyTable t;
    t.file = "summary";
    t.caption = "Medians over the scenes.";
    t.labels = {"method", "parameter"};
    t.columns = {"normal.mean_deg", "planet"};
    t.lines = {{{"ssss", "0.6"}, {{"normal.mean_deg", 1.25}, {"planet", NAN}}},
               {{"a|b, \"c\"", ""}, {{"normal.mean_deg", 2.0}}}};
    s.tables = {t};
    return s;
}

}  // namespace

TEST(StudyReport, RowsOfSeveralScenesHaveASceneColumn) {
    const tc::StudyResult s = acrossScenes();
    const std::string csv = tc::studyCsv(s);
    EXPECT_EQ(csv.rfind("scene,series,x,sets,time.total_ms", 0), 0u) << csv;
    EXPECT_NE(csv.find("\nsplash_sheet,standard depth,1000000,"), std::string::npos) << csv;
    const auto j = tc::studyJson(s);
    EXPECT_EQ(j["rows"][0]["scene"], "planet");
    ASSERT_EQ(j["tables"].size(), 1u);
    EXPECT_EQ(j["tables"][0]["lines"][0]["values"]["planet"], "NaN");
    // A study of one scene keeps its columns and keys.
    EXPECT_FALSE(tc::studyJson(twoRows())["rows"][0].contains("scene"));
    EXPECT_FALSE(tc::studyJson(twoRows()).contains("tables"));
}

TEST(StudyReport, TablesAsCsvAndMarkdown) {
    const tc::StudyResult s = acrossScenes();
    EXPECT_EQ(tc::tableCsv(s.tables[0]),
              "method,parameter,normal.mean_deg,planet\n"
              "ssss,0.6,1.25,nan\n"
              "\"a|b, \"\"c\"\"\",,2,\n");
    const std::string md = tc::studyMarkdown(s, 2);
    EXPECT_EQ(md.rfind("## Surface methods\n", 0), 0u) << md;
    EXPECT_NE(md.find("**Finding:** standard depth breaks"), std::string::npos) << md;
    EXPECT_NE(md.find("](study.svg)"), std::string::npos) << md;
    EXPECT_NE(md.find("](particle_size.svg)\n\n*Normal error against particle size.*"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| method | parameter | normal.mean_deg (°) | planet |\n"
                      "| --- | --- | ---: | ---: |\n"
                      "| ssss | 0.6 | 1.25 | NaN |\n"
                      "| a\\|b, \"c\" |  | 2 | — |\n"),
              std::string::npos)
        << md;
}

TEST(StudyReport, ScatterFiguresAndTablesAreWrittenAndShown) {
    const fs::path dir = twinrender::testing::freshDir("study_report_scenes");
    const tc::StudyResult s = acrossScenes();
    tc::writeStudy(s, dir);
    tc::writeStudiesIndex({s}, dir, "", "");
    for (const char* f : {"methods/study.svg", "methods/particle_size.svg", "methods/summary.csv",
                          "methods/study.md"})
        EXPECT_TRUE(fs::exists(dir / f)) << f;
    const auto svg = twinrender::test::checkXml(readText(dir / "methods/study.svg"));
    EXPECT_EQ(svg.error, "");
    EXPECT_EQ(svg.classCounts.at("pareto"), 2);  // the front's line and its legend entry
    const std::string html = readText(dir / "index.html");
    EXPECT_NE(html.find("<img src=\"methods/particle_size.svg\""), std::string::npos);
    EXPECT_NE(html.find("<p class=\"muted\">Normal error against particle size.</p>"),
              std::string::npos);
    EXPECT_NE(html.find("<a href=\"methods/summary.csv\">"), std::string::npos);
    EXPECT_NE(html.find("<th>Scene</th>"), std::string::npos);
    EXPECT_NE(html.find("<td>splash_sheet</td>"), std::string::npos);
    // A study without them writes none.
    const tc::StudyResult plain = twoRows();
    tc::writeStudy(plain, dir);
    tc::writeStudiesIndex({plain}, dir, "", "");
    EXPECT_FALSE(fs::exists(dir / "depth_range/study.md"));
    EXPECT_EQ(readText(dir / "index.html").find("<th>Scene</th>"), std::string::npos);
    fs::remove_all(dir);
}
