#include "report/sweep_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "report/testdata/xml_check.h"

namespace tc = twinrender::report;

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
    // "sequence" only for a sequence scene, read back (a merge keeps it).
    EXPECT_FALSE(j.contains("sequence"));
    tc::SweepReport q = sample();
    q.sequence = true;
    EXPECT_TRUE(tc::sweepFromJson(tc::sweepJson(q), "x.json").sequence);
}

TEST(SweepReport, TheFramesASequenceTimesAreItsOwn) {
    tc::SweepReport s = sample();
    EXPECT_EQ(tc::framesDescription(s), "median of 3 frames");
    s.sequence = true;
    EXPECT_EQ(tc::framesDescription(s),
              "median of the sequence's 3 frames, each a new particle set");
    EXPECT_NE(tc::sweepSvg(s).find("each a new particle set"), std::string::npos);
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

namespace {

// sample() held to thresholds: flip at most 0.15 passes rows 0 and 1 (4 and 6 ms); rows 2
// and 3 (2 and 3.5 ms, the fastest) fail it, row 3 also past a warning bound of smoothness.
tc::SweepReport checkedSample() {
    tc::SweepReport s = sample();
    s.thresholdsFile = "bounds.toml";
    for (tc::SweepRow& r : s.rows) {
        tc::Check flip;
        flip.metric = "beauty.flip";
        flip.status = r.metrics.at("beauty.flip") <= 0.15 ? tc::Status::Pass : tc::Status::Fail;
        tc::Check smooth;
        smooth.metric = "smoothness.ratio";
        smooth.status = r.index == 3 ? tc::Status::Warn : tc::Status::Pass;
        tc::recordChecks(r, {flip, smooth});
    }
    return s;
}

}  // namespace

TEST(SweepReport, ChecksGiveEachRowAVerdict) {
    const tc::SweepReport s = checkedSample();
    EXPECT_EQ(s.rows[0].status, tc::Status::Pass);
    EXPECT_TRUE(s.rows[0].failed.empty());
    EXPECT_EQ(s.rows[3].status, tc::Status::Fail);
    EXPECT_EQ(s.rows[3].failed, std::vector<std::string>{"beauty.flip"});
    EXPECT_EQ(s.rows[3].warned, std::vector<std::string>{"smoothness.ratio"});
    // A metric past both kinds of bound is listed as failed only; a row not rendered fails.
    tc::SweepRow r;
    tc::Check warn, fail;
    warn.metric = fail.metric = "beauty.flip";
    warn.status = tc::Status::Warn;
    fail.status = tc::Status::Fail;
    tc::recordChecks(r, {warn, fail});
    EXPECT_EQ(r.failed, std::vector<std::string>{"beauty.flip"});
    EXPECT_TRUE(r.warned.empty());
    r.error = "no GL";
    tc::recordChecks(r, {});
    EXPECT_EQ(r.status, tc::Status::Fail);
}

TEST(SweepReport, TheCheapestPassingRowNotTheCheapestRow) {
    tc::SweepReport s = checkedSample();
    EXPECT_EQ(tc::sweepStatus(s), tc::Status::Pass);
    ASSERT_NE(tc::cheapestRow(s), nullptr);
    EXPECT_EQ(tc::cheapestRow(s)->index, 0u);  // 4 ms; rows 2 and 3 are faster but fail
    EXPECT_EQ(tc::verdictLines(s), std::vector<std::string>{"cheapest passing: 4.00 ms: --set "
                                                            "realtime.ssss.enabled=true --set "
                                                            "realtime.shadow_map.resolution=256"});
    // None passes: why, most frequent first, and the cheapest that only warns.
    s.rows[0].status = s.rows[1].status = tc::Status::Warn;
    s.rows[0].warned = s.rows[1].warned = {"beauty.flip"};
    EXPECT_EQ(tc::sweepStatus(s), tc::Status::Warn);
    EXPECT_EQ(tc::cheapestRow(s), nullptr);
    const auto lines = tc::verdictLines(s);
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0],
              "no combination passes: beauty.flip failed in 2 of 4 combinations, beauty.flip "
              "warned in 2, smoothness.ratio warned in 1");
    EXPECT_EQ(lines[1].rfind("cheapest with warnings only: 4.00 ms: --set", 0), 0u) << lines[1];
    // Without thresholds, nothing is said.
    EXPECT_TRUE(tc::verdictLines(sample()).empty());
}

TEST(SweepReport, SetArgumentsAreQuotedForTheShellWhereNeeded) {
    tc::SweepRow r;
    r.settings = {{"camera.position", "[0,-4,1]"},
                  {"realtime.particles.normal", "gradient"},
                  {"name", "it's"}};
    EXPECT_EQ(tc::setArguments(r),
              "--set 'camera.position=[0,-4,1]' --set realtime.particles.normal=gradient "
              "--set 'name=it'\\''s'");
}

TEST(SweepReport, VerdictsInJsonCsvAndPage) {
    const tc::SweepReport s = checkedSample();
    const auto j = tc::sweepJson(s);
    EXPECT_EQ(j["thresholds"], "bounds.toml");
    EXPECT_EQ(j["rows"][3]["status"], "fail");
    EXPECT_EQ(j["rows"][3]["failed"], nlohmann::json{"beauty.flip"});
    const tc::SweepReport back = tc::sweepFromJson(nlohmann::json::parse(j.dump()), "x.json");
    EXPECT_EQ(tc::sweepJson(back), j);
    EXPECT_FALSE(tc::sweepJson(sample()).contains("thresholds"));
    EXPECT_FALSE(tc::sweepJson(sample())["rows"][0].contains("status"));

    std::istringstream csv(tc::sweepCsv(s));
    std::string header, line;
    std::getline(csv, header);
    EXPECT_EQ(header.rfind("index,realtime.ssss.enabled,realtime.shadow_map.resolution,status,"
                           "failed,warned,time.total_ms,",
                           0),
              0u)
        << header;
    for (int i = 0; i < 4; ++i) std::getline(csv, line);
    EXPECT_EQ(line.rfind("3,false,1024,fail,beauty.flip,smoothness.ratio,3.5,", 0), 0u) << line;

    const std::string html = tc::sweepHtml(s);
    EXPECT_NE(html.find("Cheapest passing combination"), std::string::npos);
    EXPECT_NE(html.find("<pre class=\"command\"><code>--set realtime.ssss.enabled=true --set "
                        "realtime.shadow_map.resolution=256</code></pre>"),
              std::string::npos);
    EXPECT_NE(html.find("<th>Verdict</th>"), std::string::npos);
    EXPECT_NE(html.find("<td class=\"num fail\">0.2</td>"), std::string::npos);
    EXPECT_EQ(tc::sweepHtml(sample()).find("<th>Verdict</th>"), std::string::npos);
}
