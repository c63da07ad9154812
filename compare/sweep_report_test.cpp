#include "compare/sweep_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "compare/testdata/xml_check.h"
#include "core/error.h"

namespace tc = twinrender::compare;

namespace {

tc::SweepReport sample() {
    tc::SweepReport s;
    s.scene = "planet";
    s.sceneFile = "scenes/planet.toml";
    s.referenceDescription = "raymarch (scene settings)";
    s.keys = {"realtime.ssss.enabled", "realtime.shadow_map.resolution"};
    s.frames = 3;
    s.combinations = 4;
    s.commandLine = "twinrender sweep scenes/planet.toml --vary ...";
    const double flips[] = {0.10, 0.12, 0.20, 0.21};
    const double times[] = {4.0, 6.0, 2.0, 3.5};
    for (std::size_t i = 0; i < 4; ++i) {
        tc::SweepRow r;
        r.index = i;
        r.settings = {{"realtime.ssss.enabled", i < 2 ? "true" : "false"},
                      {"realtime.shadow_map.resolution", i % 2 ? "1024" : "256"}};
        r.timingsMs = {{"total", times[i]}, {"ssss", i < 2 ? 1.5 : 0.0}};
        r.metrics = {
            {"beauty.flip", flips[i]}, {"beauty.psnr", INFINITY}, {"normal.mean_deg", NAN}};
        r.dir = "combinations/c00" + std::to_string(i);
        r.referenceKey = "abc";
        s.rows.push_back(r);
    }
    return s;
}

}  // namespace

TEST(SweepReport, LabelsDropTheSection) {
    EXPECT_EQ(sample().rows[0].label(), "ssss.enabled=true, shadow_map.resolution=256");
    tc::SweepRow r;
    r.settings = {{"camera.width", "64"}};
    EXPECT_EQ(r.label(), "camera.width=64");
}

TEST(SweepReport, JsonRoundTrip) {
    const tc::SweepReport s = sample();
    const auto j = tc::sweepJson(s);
    EXPECT_EQ(j["better"], "lower");
    EXPECT_EQ(j["rows"].size(), 4u);
    const tc::SweepReport back = tc::sweepFromJson(nlohmann::json::parse(j.dump()), "x.json");
    EXPECT_EQ(tc::sweepJson(back), j);
    EXPECT_TRUE(std::isinf(back.rows[1].metrics.at("beauty.psnr")));
    EXPECT_THROW(tc::sweepFromJson(nlohmann::json{{"format", "other"}}, "x.json"),
                 twinrender::core::InputError);
}

TEST(SweepReport, CsvHasOneLinePerRowAndTheSettingsColumns) {
    const std::string csv = tc::sweepCsv(sample());
    std::istringstream in(csv);
    std::string header, line;
    std::getline(in, header);
    EXPECT_EQ(
        header,
        "index,realtime.ssss.enabled,realtime.shadow_map.resolution,time.total_ms,time.ssss_ms,"
        "beauty.psnr,beauty.flip,normal.mean_deg,dir,error");
    std::getline(in, line);
    EXPECT_EQ(line, "0,true,256,4,1.5,inf,0.1,nan,combinations/c000,");
    int n = 1;
    while (std::getline(in, line)) ++n;
    EXPECT_EQ(n, 4);
}

TEST(SweepReport, ChartAndPage) {
    const tc::SweepReport s = sample();
    const std::string svg = tc::sweepSvg(s);
    const auto xml = twinrender::test::checkXml(svg);
    ASSERT_EQ(xml.error, "") << svg;
    EXPECT_EQ(xml.classCounts.at("point"), 4 + 2);  // rows + legend
    // Front by (time, flip): (2, 0.20), (4, 0.10); (3.5, 0.21) and (6, 0.12) are beaten.
    EXPECT_EQ(xml.classCounts.at("pareto-point"), 2 + 1);
    EXPECT_NE(svg.find("beauty.flip (lower is better)"), std::string::npos);
    const std::string html = tc::sweepHtml(s);
    EXPECT_NE(html.find("<img src=\"sweep.svg\""), std::string::npos);
    EXPECT_NE(html.find("id=\"selftest\""), std::string::npos);
    EXPECT_NE(html.find("twinrender sweep scenes/planet.toml"), std::string::npos);
    EXPECT_NE(html.find("combinations/c002/realtime.png"), std::string::npos);
}

TEST(SweepReport, ChartValueOfATargetMetricIsTheDistance) {
    std::string label;
    EXPECT_DOUBLE_EQ(tc::chartValue("smoothness.ratio", 0.8, &label), 0.2);
    EXPECT_NE(label.find("lower is better"), std::string::npos);
    EXPECT_FALSE(tc::lowerIsBetter("beauty.ssim"));
    EXPECT_TRUE(tc::lowerIsBetter("beauty.flip"));
}
