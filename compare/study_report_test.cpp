#include "compare/study_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "compare/testdata/xml_check.h"
#include "tests/scratch_dir.h"

namespace tc = twinrender::compare;
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

std::string readText(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

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
    fs::remove_all(dir);
}
