#include "compare/report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "compare/testdata/synthetic_report.h"
#include "core/error.h"
#include "core/image_io.h"
#include "tests/scratch_dir.h"

namespace twinrender::compare {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path freshDir(const std::string& name) { return twinrender::testing::freshDir("report_" + name); }

std::string readText(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + what.size()))
        ++n;
    return n;
}

std::string percentDecode(const std::string& s) {
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '%' && i + 2 < s.size()) {
            out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += s[i];
        }
    }
    return out;
}

SceneReport sceneWithChecks() {
    SceneReport s;
    s.name = "planet";
    s.metrics = {{"beauty.psnr", std::numeric_limits<double>::infinity()},
                 {"beauty.flip", 0.2},
                 {"shadow.iou", 0.97}};
    const Thresholds t = Thresholds::parseString(
        "\"beauty.flip\" = { max = 0.15 }\n\"shadow.iou\" = { min = 0.9, warn_min = 0.98 }\n"
        "\"coverage.iou\" = { min = 0.9 }\n",
        "t.toml");
    s.checks = evaluate(s.metrics, t.global());
    Baseline b;
    b.scenes["planet"].metrics = {{"beauty.flip", 0.1}};
    const auto bc = compareToBaseline("planet", s.metrics, b);
    s.checks.insert(s.checks.end(), bc.begin(), bc.end());
    s.renderers["realtime"].timingsMs = {{"total", 4.0}, {"ssss", 1.5}};
    s.renderers["raymarch"].timingsMs = {{"total", 400.0}};
    return s;
}

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

TEST(ReportJunit, OneTestcasePerSceneAndCheckedMetric) {
    RunReport run;
    run.scenes.push_back(sceneWithChecks());
    SceneReport ok;
    ok.name = "contact";
    run.scenes.push_back(ok);
    SceneReport broken;
    broken.name = "ring<world>";
    broken.error = "no \"GL\" & no luck";
    run.scenes.push_back(broken);
    const std::string xml = junitXml(run);
    EXPECT_EQ(xml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>", 0), 0u);
    EXPECT_EQ(count(xml, "<testsuite "), 1u);
    EXPECT_EQ(count(xml, "</testsuite>"), 1u);
    // planet: beauty.flip, coverage.iou, shadow.iou; contact: render; ring<world>: render.
    EXPECT_EQ(count(xml, "<testcase "), 5u);
    EXPECT_EQ(count(xml, "<failure "), 2u);  // beauty.flip (max and baseline), coverage.iou
    EXPECT_EQ(count(xml, "<error "), 1u);
    EXPECT_EQ(count(xml, "<system-out>"), 2u);  // shadow.iou's warning, contact's note
    EXPECT_NE(xml.find("tests=\"5\" failures=\"2\" errors=\"1\""), std::string::npos) << xml;
    EXPECT_NE(xml.find("<testcase classname=\"twinrender.planet\" name=\"beauty.flip\""),
              std::string::npos);
    EXPECT_NE(xml.find("<property name=\"value\" value=\"0.2\"/>"), std::string::npos) << xml;
    EXPECT_NE(xml.find("<property name=\"max\" value=\"0.15\"/>"), std::string::npos) << xml;
    EXPECT_NE(xml.find("<property name=\"baseline\" value=\"0.1\"/>"), std::string::npos) << xml;
    EXPECT_NE(
        xml.find("<failure message=\"beauty.flip = 0.2 is above its max 0.15 (t.toml:1:25)\""),
        std::string::npos)
        << xml;
    EXPECT_NE(xml.find("beauty.flip got worse than the baseline: 0.1 -&gt; 0.2"), std::string::npos)
        << xml;
    EXPECT_NE(xml.find("warning: shadow.iou = 0.97 is below its warn_min 0.98"), std::string::npos)
        << xml;
    EXPECT_NE(xml.find("classname=\"twinrender.ring&lt;world&gt;\""), std::string::npos) << xml;
    EXPECT_NE(xml.find("message=\"no &quot;GL&quot; &amp; no luck\""), std::string::npos) << xml;
    // Every element opened is closed.
    EXPECT_EQ(count(xml, "<testcase "), count(xml, "</testcase>") + count(xml, "\"0\"/>"));
    EXPECT_EQ(count(xml, "<properties>"), count(xml, "</properties>"));
}

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
            EXPECT_TRUE(fs::is_regular_file(e.path().parent_path() / percentDecode(src)))
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

TEST(BufferImages, VisualisationsFollowTheirConventions) {
    core::Image aov = core::aov::makeImage(4, 1);
    auto set = [&](int x, const char* ch, float v) { aov.at(x, 0, aov.channelIndex(ch)) = v; };
    for (int x = 0; x < 3; ++x) set(x, "A", 1.0f);
    set(0, "N.Z", 1.0f);
    set(0, "Z", 1.0f);
    set(1, "Z", 10.0f);
    set(2, "Z", 100.0f);
    set(0, "uv.U", 0.25f);
    set(0, "uv.V", 0.75f);
    set(0, "id", 0.0f);
    set(1, "id", 1.0f);
    set(2, "id", 0.0f);
    set(0, "shadow", 1.0f);

    const core::Image n = visualiseBuffer(aov, "normal");
    EXPECT_FLOAT_EQ(n.at(0, 0, 0), 0.5f);
    EXPECT_FLOAT_EQ(n.at(0, 0, 1), 0.5f);
    EXPECT_FLOAT_EQ(n.at(0, 0, 2), 1.0f);
    const core::Image uv = visualiseBuffer(aov, "uv");
    EXPECT_FLOAT_EQ(uv.at(0, 0, 0), 0.25f);
    EXPECT_FLOAT_EQ(uv.at(0, 0, 1), 0.75f);
    EXPECT_FLOAT_EQ(uv.at(0, 0, 2), 0.0f);
    // Depth: log-scaled, near white, far grey; 10 is halfway between 1 and 100.
    const core::Image d = visualiseBuffer(aov, "depth");
    EXPECT_FLOAT_EQ(d.at(0, 0, 0), 1.0f);
    EXPECT_NEAR(d.at(1, 0, 0), 1.0f - 0.375f, 1e-6);
    EXPECT_FLOAT_EQ(d.at(2, 0, 0), 0.25f);
    // A shared range shifts the mapping.
    BufferVisualSettings wide;
    wide.depthRange = {0.1, 1000.0};
    EXPECT_LT(visualiseBuffer(aov, "depth", wide).at(0, 0, 0), 1.0f);
    // Ids: one colour per body, the same wherever it appears; background differs from all.
    const core::Image id = visualiseBuffer(aov, "id");
    EXPECT_EQ(id.at(0, 0, 0), id.at(2, 0, 0));
    float diff = 0.0f;
    for (int c = 0; c < 3; ++c) diff += std::abs(id.at(0, 0, c) - id.at(1, 0, c));
    EXPECT_GT(diff, 0.3f);
    const core::Image sh = visualiseBuffer(aov, "shadow");
    EXPECT_FLOAT_EQ(sh.at(0, 0, 0), 1.0f);
    EXPECT_FLOAT_EQ(sh.at(1, 0, 0), 0.3f);
    // No coverage: the same slate background in every buffer but beauty.
    for (const char* b : {"normal", "uv", "depth", "id", "shadow", "emission"})
        EXPECT_NEAR(visualiseBuffer(aov, b).at(3, 0, 0), 0.10f, 1e-6) << b;

    core::Image rgbOnly(2, 2, {"R", "G", "B"});
    EXPECT_THROW(visualiseBuffer(rgbOnly, "normal"), core::NotComparableError);
    EXPECT_THROW(visualiseBuffer(aov, "albedo"), std::invalid_argument);
}

TEST(BufferImages, WritesOnePngPerAvailableBuffer) {
    const fs::path dir = freshDir("buffers");
    const core::Image aov = testdata::syntheticAov(16, 12, 8.0, 6.0, 5.0);
    const auto files = writeBufferImages(aov, nullptr, dir, "realtime");
    ASSERT_EQ(files.size(), bufferNames().size());
    for (const auto& [buffer, name] : files) {
        EXPECT_EQ(name, "realtime." + buffer + ".png");
        const core::Image png = core::readImage(dir / name);
        EXPECT_EQ(png.width(), 16);
        EXPECT_EQ(png.height(), 12);
    }
    core::Image beautyOnly(16, 12, {"R", "G", "B"});
    EXPECT_EQ(writeBufferImages(beautyOnly, nullptr, dir, "plain").size(), 1u);
}

TEST(ErrorMaps, MagmaRunsFromBlackToPaleYellow) {
    float lo[3], mid[3], hi[3];
    magma(0.0, lo);
    magma(0.5, mid);
    magma(1.0, hi);
    EXPECT_NEAR(lo[0], 0.001462f, 1e-6);
    EXPECT_NEAR(lo[2], 0.013866f, 1e-6);
    EXPECT_NEAR(hi[0], 0.987053f, 1e-6);
    EXPECT_NEAR(hi[2], 0.749504f, 1e-6);
    // matplotlib's magma(0.5) = (0.716387, 0.214982, 0.475290) (entry 128 of 256).
    EXPECT_NEAR(mid[0], 0.716387f, 5e-3);
    EXPECT_NEAR(mid[1], 0.214982f, 5e-3);
    // Luminance rises monotonically, as a perceptual map's must.
    float prev = -1.0f;
    for (int i = 0; i <= 100; ++i) {
        float c[3];
        magma(i / 100.0, c);
        const float y = 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
        EXPECT_GT(y, prev) << i;
        prev = y;
    }
    core::Image map(3, 1, {"flip"});
    map.at(0, 0, 0) = 0.0f;
    map.at(1, 0, 0) = 2.0f;  // beyond the range: clamped
    map.at(2, 0, 0) = std::nanf("");
    const core::Image c = colourMapped(map, 0, 0.0, 1.0);
    EXPECT_NEAR(c.at(1, 0, 0), 0.987053f, 1e-6);
    EXPECT_EQ(c.at(2, 0, 0), 0.0f);
}

TEST(ErrorMaps, WritesTheMetricsErrorMapsWithFixedRanges) {
    const fs::path dir = freshDir("error_maps");
    std::map<std::string, core::Image> maps;
    for (const char* key : {"beauty.flip", "normal", "emission"}) {
        core::Image m(4, 2, {"e"});
        m.at(1, 0, 0) = 0.5f;
        maps[key] = m;
    }
    const auto images = writeErrorMapImages(maps, dir);
    ASSERT_EQ(images.size(), 3u);
    EXPECT_EQ(images.at("beauty").path, "error.beauty.png");
    EXPECT_EQ(images.at("beauty").label, "ꟻLIP error");
    EXPECT_DOUBLE_EQ(images.at("beauty").hi, 1.0);
    EXPECT_DOUBLE_EQ(images.at("normal").hi, 30.0);
    EXPECT_EQ(images.at("normal").unit, "°");
    EXPECT_DOUBLE_EQ(images.at("emission").hi, 0.5);  // its own maximum
    for (const auto& [buffer, m] : images) {
        const core::Image png = core::readImage(dir / m.path);
        EXPECT_EQ(png.width(), 4) << buffer;
    }
}

TEST(ReportUnits, MetricUnits) {
    EXPECT_EQ(metricUnit("beauty.psnr"), "dB");
    EXPECT_EQ(metricUnit("normal.mean_deg"), "°");
    EXPECT_EQ(metricUnit("silhouette.mean_px"), "px");
    EXPECT_EQ(metricUnit("time.realtime_ms"), "ms");
    EXPECT_EQ(metricUnit("beauty.ssim"), "");
}

}  // namespace
}  // namespace twinrender::compare
