#include "report/report_html.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/image_io.h"
#include "report/buffer_display.h"
#include "report/junit.h"
#include "report/markup.h"
#include "report/testdata/read_text.h"
#include "report/testdata/synthetic_report.h"
#include "tests/scratch_dir.h"

namespace twinrender::report {
namespace {

using namespace twinrender::compare;  // what the report shows

namespace fs = std::filesystem;
using nlohmann::json;

fs::path freshDir(const std::string& name) {
    return twinrender::testing::freshDir("report_" + name);
}

using testdata::readText;

TEST(ReportHtml, EveryImageExistsAndNothingComesFromTheNetwork) {
    const fs::path dir = freshDir("html");
    const RunReport run = testdata::syntheticReport(dir);
    writeReport(run, dir);
    writeJunit(run, dir / "junit.xml");
    for (const char* f :
         {"index.html", "summary.json", "junit.xml", "sphere/index.html", "sphere/metrics.json",
          "sphere_shifted/index.html", "sphere_shifted/metrics.json"})
        EXPECT_TRUE(fs::is_regular_file(dir / f)) << f;

    const std::regex img("<img[^>]*\\ssrc=\"([^\"]*)\"");
    std::size_t pages = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        if (e.path().extension() != ".html") continue;
        ++pages;
        const std::string html = readText(e.path());
        EXPECT_EQ(html.find("http://"), std::string::npos) << e.path();
        EXPECT_EQ(html.find("https://"), std::string::npos) << e.path();
        EXPECT_EQ(html.find("//cdn"), std::string::npos) << e.path();
        EXPECT_NE(html.find("<pre id=\"selftest\""), std::string::npos) << e.path();
        std::size_t images = 0;
        for (auto it = std::sregex_iterator(html.begin(), html.end(), img);
             it != std::sregex_iterator(); ++it) {
            const std::string src = (*it)[1];
            ++images;
            EXPECT_FALSE(src.empty()) << e.path();
            EXPECT_TRUE(fs::is_regular_file(e.path().parent_path() / pathOfUrl(src)))
                << src << " in " << e.path();
        }
        EXPECT_GT(images, 0u) << e.path();
    }
    EXPECT_EQ(pages, 3u);

    const std::string scene = readText(dir / "sphere_shifted" / "index.html");
    for (const auto& b : bufferNames())
        EXPECT_NE(scene.find("data-buffer=\"" + b + "\""), std::string::npos) << b;
    EXPECT_NE(scene.find("<span class=\"badge fail\">fail</span>"), std::string::npos);
    EXPECT_NE(scene.find("shadow.iou got worse than the baseline"), std::string::npos);
    EXPECT_NE(scene.find("realtime.ssss.enabled: true -&gt; false"), std::string::npos);
    EXPECT_NE(scene.find("id=\"swap-range\""), std::string::npos);
    EXPECT_NE(scene.find("ꟻLIP error"), std::string::npos);
    // HDR-ꟻLIP's map beside ꟻLIP's, under the beauty buffer, its exposures in the caption.
    const std::size_t beautyMaps = scene.find("<div data-buffer=\"beauty\"><div class=\"frame\">");
    ASSERT_NE(beautyMaps, std::string::npos);
    const std::size_t hdrMap = scene.find("src=\"hdrflip.png\"");
    ASSERT_NE(hdrMap, std::string::npos);
    EXPECT_LT(scene.find("src=\"flip.png\""), hdrMap);
    EXPECT_GT(hdrMap, beautyMaps);
    EXPECT_LT(hdrMap, scene.find("</figure>", beautyMaps));
    EXPECT_NE(scene.find("<b>HDR-ꟻLIP error</b><span>2 exposures, "), std::string::npos);
    EXPECT_NE(scene.find(" stops</span>"), std::string::npos);
    const std::string index = readText(dir / "index.html");
    EXPECT_NE(index.find("href=\"sphere/index.html\""), std::string::npos);
    EXPECT_NE(index.find("href=\"sphere_shifted/index.html\""), std::string::npos);
    EXPECT_NE(index.find("340×"), std::string::npos);  // 850 ms over 2.5 ms

    const json summary = json::parse(readText(dir / "summary.json"));
    EXPECT_EQ(summary["status"], "fail");
    EXPECT_EQ(summary["scenes"][0]["status"], "pass");
    EXPECT_EQ(summary["scenes"][1]["status"], "fail");
}

TEST(ReportHtml, NamesAreEscapedAndPathsEncoded) {
    const fs::path dir = freshDir("escape");
    RunReport run;
    SceneReport s;
    s.name = "a b&<c>";
    s.description = "<script>alert(1)</script>";
    fs::create_directories(dir / s.name);
    core::writeImage(core::Image(2, 2, {"R", "G", "B"}), dir / s.name / "beauty #1.png");
    s.renderers["realtime"].images["beauty"] = "beauty #1.png";
    run.scenes.push_back(s);
    writeHtmlReport(run, dir);
    const std::string index = readText(dir / "index.html");
    EXPECT_EQ(index.find("<script>alert"), std::string::npos);
    EXPECT_NE(index.find("&lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
    EXPECT_NE(index.find("src=\"a%20b%26%3Cc%3E/beauty%20%231.png\""), std::string::npos) << index;
    EXPECT_TRUE(fs::is_regular_file(dir / s.name / "index.html"));
}

TEST(ReportHtml, SettingsAreNamedByTheirDottedKeys) {
    const fs::path dir = freshDir("settings");
    RunReport run;
    SceneReport s;
    s.name = "planet";
    s.settings = {{"scene_file", "scenes/planet.toml"},
                  {"realtime", {{"realtime.ssss.radius_scale", 0.6}}}};
    run.scenes.push_back(s);
    writeHtmlReport(run, dir);
    const std::string page = readText(dir / "planet" / "index.html");
    EXPECT_NE(page.find("<tr><td>realtime.ssss.radius_scale</td><td>0.6</td></tr>"),
              std::string::npos)
        << page;
    EXPECT_EQ(page.find("realtime.realtime."), std::string::npos);
}

}  // namespace
}  // namespace twinrender::report
