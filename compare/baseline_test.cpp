#include "compare/baseline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "tests/scratch_dir.h"

namespace twinrender::compare {
namespace {

using nlohmann::json;

const double INF = std::numeric_limits<double>::infinity();

Baseline oneScene(MetricValues metrics, json settings = nullptr) {
    Baseline b;
    b.file = "base.json";
    b.scenes["planet"] = {std::move(metrics), std::move(settings)};
    return b;
}

Check only(const std::vector<Check>& checks) {
    EXPECT_EQ(checks.size(), 1u);
    return checks.front();
}

TEST(BaselinePolicy, DirectionsAndDefaults) {
    EXPECT_EQ(defaultPolicy("beauty.psnr").better, Better::Higher);
    EXPECT_EQ(defaultPolicy("beauty.ssim").better, Better::Higher);
    EXPECT_EQ(defaultPolicy("coverage.iou").better, Better::Higher);
    EXPECT_EQ(defaultPolicy("shadow.iou").better, Better::Higher);
    EXPECT_EQ(defaultPolicy("beauty.flip").better, Better::Lower);
    EXPECT_EQ(defaultPolicy("normal.p95_deg").better, Better::Lower);
    EXPECT_EQ(defaultPolicy("shadow.false_shadow").better, Better::Lower);
    EXPECT_EQ(defaultPolicy("smoothness.ratio").better, Better::Closer);
    EXPECT_DOUBLE_EQ(defaultPolicy("smoothness.ratio").origin, 1.0);
    EXPECT_TRUE(defaultPolicy("beauty.flip").checked);
    EXPECT_FALSE(defaultPolicy("time.realtime_ms").checked);  // times are noisy
    EXPECT_DOUBLE_EQ(defaultPolicy("beauty.flip").relative, 0.02);
    // 2 % of the remaining error, at least the absolute part.
    EXPECT_DOUBLE_EQ(allowedWorsening(defaultPolicy("beauty.flip"), 0.2), 0.004);
    EXPECT_DOUBLE_EQ(allowedWorsening(defaultPolicy("beauty.flip"), 0.0), 1e-3);
    EXPECT_NEAR(allowedWorsening(defaultPolicy("coverage.iou"), 0.5), 0.01, 1e-15);
    EXPECT_NEAR(allowedWorsening(defaultPolicy("beauty.psnr"), 35.0), 0.7, 1e-12);
    EXPECT_DOUBLE_EQ(allowedWorsening(defaultPolicy("beauty.psnr"), INF), 0.1);
}

TEST(CompareToBaseline, WorseBeyondToleranceFailsNamingTheChange) {
    const Baseline b = oneScene({{"beauty.flip", 0.05}});
    const Check c = only(compareToBaseline("planet", {{"beauty.flip", 0.08}}, b));
    EXPECT_EQ(c.status, Status::Fail);
    EXPECT_EQ(c.bound, "baseline");
    ASSERT_TRUE(c.baseline);
    EXPECT_DOUBLE_EQ(*c.baseline, 0.05);
    EXPECT_DOUBLE_EQ(c.value, 0.08);
    EXPECT_DOUBLE_EQ(c.limit, 0.051);
    EXPECT_EQ(c.where, "base.json");
    // The metric, the baseline value, the new value and the delta.
    EXPECT_NE(c.message.find("beauty.flip got worse than the baseline: 0.05 -> 0.08 (delta +0.03, "
                             "+60.0 %)"),
              std::string::npos)
        << c.message;
    EXPECT_NE(c.message.find("tolerance allows 0.001"), std::string::npos) << c.message;
}

TEST(CompareToBaseline, BetterAndWithinTolerancePass) {
    const Baseline b =
        oneScene({{"beauty.flip", 0.05}, {"beauty.psnr", 30.0}, {"coverage.iou", 0.99}});
    auto status = [&](const std::string& metric, double v) {
        return only(compareToBaseline(
                        "planet", {{metric, v}},
                        oneScene({{metric, b.scenes.at("planet").metrics.at(metric)}})))
            .status;
    };
    EXPECT_EQ(status("beauty.flip", 0.04), Status::Pass);    // better
    EXPECT_EQ(status("beauty.flip", 0.0509), Status::Pass);  // worse by 0.0009 < 0.001
    EXPECT_EQ(status("beauty.flip", 0.0511), Status::Fail);
    EXPECT_EQ(status("beauty.psnr", 31.0), Status::Pass);
    EXPECT_EQ(status("beauty.psnr", 29.5), Status::Pass);  // 2 % of 30 dB = 0.6 dB
    EXPECT_EQ(status("beauty.psnr", 29.3), Status::Fail);
    EXPECT_EQ(status("coverage.iou", 0.9895), Status::Pass);  // at least 0.001
    EXPECT_EQ(status("coverage.iou", 0.985), Status::Fail);
    const Check better = only(
        compareToBaseline("planet", {{"beauty.flip", 0.04}}, oneScene({{"beauty.flip", 0.05}})));
    EXPECT_NE(better.message.find("better than the baseline: 0.05 -> 0.04 (delta -0.01, -20.0 %)"),
              std::string::npos)
        << better.message;
}

TEST(CompareToBaseline, CloserToTheTargetIsBetter) {
    const Baseline b = oneScene({{"smoothness.ratio", 1.1}});
    EXPECT_EQ(only(compareToBaseline("planet", {{"smoothness.ratio", 0.95}}, b)).status,
              Status::Pass);
    EXPECT_EQ(only(compareToBaseline("planet", {{"smoothness.ratio", 1.105}}, b)).status,
              Status::Pass);
    const Check c = only(compareToBaseline("planet", {{"smoothness.ratio", 0.8}}, b));
    EXPECT_EQ(c.status, Status::Fail);
    EXPECT_NEAR(c.limit, 0.89, 1e-12);  // |1.1 - 1| + 0.01 below 1
}

TEST(CompareToBaseline, InfinitePsnrMustStayInfinite) {
    const Baseline b = oneScene({{"beauty.psnr", INF}});
    EXPECT_EQ(only(compareToBaseline("planet", {{"beauty.psnr", INF}}, b)).status, Status::Pass);
    EXPECT_EQ(only(compareToBaseline("planet", {{"beauty.psnr", 60.0}}, b)).status, Status::Fail);
}

TEST(CompareToBaseline, MissingOrNanFailsAndTimesAreNotChecked) {
    const Baseline b =
        oneScene({{"beauty.flip", 0.05}, {"shadow.iou", 0.9}, {"time.raymarch_ms", 100.0}});
    const auto checks = compareToBaseline(
        "planet", {{"beauty.flip", std::nan("")}, {"time.raymarch_ms", 900.0}}, b);
    ASSERT_EQ(checks.size(), 2u);  // no check for the time
    EXPECT_EQ(checks[0].metric, "beauty.flip");
    EXPECT_EQ(checks[0].status, Status::Fail);
    EXPECT_NE(checks[0].message.find("not computable"), std::string::npos) << checks[0].message;
    EXPECT_EQ(checks[1].metric, "shadow.iou");
    EXPECT_EQ(checks[1].status, Status::Fail);
    EXPECT_NE(checks[1].message.find("not computed"), std::string::npos) << checks[1].message;
    // Times are checked when the file says so.
    Baseline timed = b;
    timed.tolerances["time.raymarch_ms"] = defaultPolicy("time.raymarch_ms");
    timed.tolerances["time.raymarch_ms"].checked = true;
    const auto t = compareToBaseline(
        "planet", {{"beauty.flip", 0.05}, {"shadow.iou", 0.9}, {"time.raymarch_ms", 900.0}}, timed);
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[2].metric, "time.raymarch_ms");
    EXPECT_EQ(t[2].status, Status::Fail);
}

TEST(CompareToBaseline, NewScenesAndNewMetricsAreNotChecked) {
    const Baseline b = oneScene({{"beauty.flip", 0.05}});
    EXPECT_TRUE(compareToBaseline("ringworld", {{"beauty.flip", 0.9}}, b).empty());
    EXPECT_EQ(compareToBaseline("planet", {{"beauty.flip", 0.05}, {"uv.mean", 9.0}}, b).size(), 1u);
}

TEST(CompareToBaseline, FailureNamesTheSettingsThatChanged) {
    const json before = {{"realtime", {{"ssss", {{"enabled", true}}}, {"depth", "log"}}}};
    const json after = {
        {"realtime", {{"ssss", {{"enabled", false}}}, {"depth", "log"}, {"bloom", 1}}}};
    const Baseline b = oneScene({{"normal.mean_deg", 2.0}}, before);
    const Check c = only(compareToBaseline("planet", {{"normal.mean_deg", 9.0}}, b, &after));
    EXPECT_EQ(c.status, Status::Fail);
    EXPECT_NE(c.message.find("settings changed since the baseline: realtime.ssss.enabled: true -> "
                             "false, realtime.bloom: added (1)"),
              std::string::npos)
        << c.message;
    const Check same = only(compareToBaseline("planet", {{"normal.mean_deg", 9.0}}, b, &before));
    EXPECT_NE(same.message.find("settings are the same"), std::string::npos) << same.message;
}

// A run records each renderer's settings by their full dotted keys under the renderer's name
// (compare/settings_keys.h); a message names a setting once, as the user writes it.
TEST(CompareToBaseline, ChangedSettingsHaveTheDottedNameAUserWrites) {
    const json before = {{"scene_file", "scenes/planet.toml"},
                         {"realtime", {{"realtime.ssss.radius_scale", 0.6}}},
                         {"raymarch", {{"raymarch.spp", 1}}}};
    json after = before;
    after["realtime"]["realtime.ssss.radius_scale"] = 1.2;
    const Baseline b = oneScene({{"normal.mean_deg", 2.0}}, before);
    const Check c = only(compareToBaseline("planet", {{"normal.mean_deg", 9.0}}, b, &after));
    const std::string expected =
        "; settings changed since the baseline: realtime.ssss.radius_scale: 0.6 -> 1.2";
    ASSERT_GE(c.message.size(), expected.size()) << c.message;
    EXPECT_EQ(c.message.substr(c.message.size() - expected.size()), expected) << c.message;
    EXPECT_EQ(settingsChanges(before, after),
              std::vector<std::string>{"realtime.ssss.radius_scale: 0.6 -> 1.2"});
}

json summary() {
    return json::parse(R"({
      "status": "fail",
      "scenes": [
        {"name": "planet", "status": "pass",
         "metrics": {"beauty.psnr": "Infinity", "beauty.flip": 0.0, "shadow.iou": "NaN",
                     "time.realtime_ms": 3.5},
         "settings": {"realtime": {"depth": "log"}}},
        {"name": "broken", "status": "fail", "metrics": {}, "error": "no GL"}
      ]})");
}

TEST(Bless, TakesEveryFiniteOrInfiniteMetricWithItsPolicy) {
    const Baseline b = bless(summary(), "runs/a/summary.json");
    EXPECT_EQ(b.blessedFrom, "runs/a/summary.json");
    ASSERT_EQ(b.scenes.size(), 1u);  // a scene without metrics has nothing to bless
    const MetricValues& m = b.scenes.at("planet").metrics;
    EXPECT_EQ(m.size(), 3u);  // NaN is not blessed
    EXPECT_EQ(m.at("beauty.psnr"), INF);
    EXPECT_EQ(m.at("time.realtime_ms"), 3.5);
    EXPECT_EQ(b.scenes.at("planet").settings["realtime"]["depth"], "log");
    EXPECT_EQ(b.tolerances.size(), 3u);
    EXPECT_FALSE(b.tolerances.at("time.realtime_ms").checked);
    EXPECT_EQ(b.metrics("planet"), &m);
    EXPECT_EQ(b.metrics("nowhere"), nullptr);
}

TEST(Bless, RejectsWhatIsNotASummary) {
    EXPECT_THROW(bless(json::parse(R"({"scenes": 3})"), "x.json"), core::InputError);
    EXPECT_THROW(bless(json::parse(R"({"scenes": [{"metrics": {}}]})"), "x.json"),
                 core::InputError);
    try {
        bless(json::parse(R"({"scenes": [{"name": "a", "metrics": {"beauty.flip": "low"}}]})"),
              "x.json");
        FAIL();
    } catch (const core::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("scenes[0].metrics.beauty.flip"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(blessRunDir("/nonexistent/run"), core::InputError);
}

TEST(BaselineFile, RoundTripsThroughJsonAndDisk) {
    Baseline b = bless(summary(), "runs/a/summary.json");
    b.tolerances["beauty.flip"].absolute = 0.005;
    const json j = toJson(b);
    EXPECT_EQ(j["format"], "twinrender-baseline");
    EXPECT_EQ(j["version"], 1);
    EXPECT_EQ(j["scenes"]["planet"]["metrics"]["beauty.psnr"], "Infinity");
    EXPECT_EQ(j["tolerances"]["beauty.flip"]["better"], "lower");

    const auto path = twinrender::testing::scratchFile("baseline_test.json");
    writeBaseline(b, path);
    const Baseline r = readBaseline(path);
    EXPECT_EQ(r.file, path.string());
    EXPECT_EQ(r.blessedFrom, b.blessedFrom);
    EXPECT_EQ(r.scenes.at("planet").metrics, b.scenes.at("planet").metrics);
    EXPECT_EQ(r.scenes.at("planet").settings, b.scenes.at("planet").settings);
    EXPECT_DOUBLE_EQ(r.policy("beauty.flip").absolute, 0.005);
    EXPECT_EQ(r.policy("beauty.psnr").better, Better::Higher);
    EXPECT_EQ(r.policy("time.realtime_ms").checked, false);
    std::filesystem::remove(path);
}

TEST(BaselineFile, RejectsBadFilesNamingTheKey) {
    auto message = [](const char* text) {
        try {
            parseBaseline(json::parse(text), "b.json");
        } catch (const core::InputError& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    EXPECT_NE(message(R"({"scenes": {}})").find("not a twinrender baseline"), std::string::npos);
    EXPECT_NE(message(R"({"format": "twinrender-baseline", "version": 2})").find("'version'"),
              std::string::npos);
    EXPECT_NE(
        message(R"({"format": "twinrender-baseline", "version": 1, "extra": 1})").find("'extra'"),
        std::string::npos);
    const std::string neg = message(
        R"({"format": "twinrender-baseline", "version": 1,
            "tolerances": {"beauty.flip": {"relative": -1}}})");
    EXPECT_NE(neg.find("b.json: key 'tolerances.beauty.flip.relative' must be >= 0"),
              std::string::npos)
        << neg;
    EXPECT_NE(message(R"({"format": "twinrender-baseline", "version": 1,
                          "scenes": {"a": {"metrics": {"x": "big"}}}})")
                  .find("'scenes.a.metrics.x'"),
              std::string::npos);
    EXPECT_THROW(readBaseline("/nonexistent/baseline.json"), core::InputError);
}

TEST(SettingsChanges, ListsChangedAddedAndRemovedKeys) {
    const auto c = settingsChanges(json{{"a", 1}, {"b", {{"c", "x"}}}, {"gone", true}},
                                   json{{"a", 2}, {"b", {{"c", "x"}}}, {"new", 0.5}});
    ASSERT_EQ(c.size(), 3u);
    EXPECT_EQ(c[0], "a: 1 -> 2");
    EXPECT_EQ(c[1], "gone: removed (was true)");
    EXPECT_EQ(c[2], "new: added (0.5)");
}

}  // namespace
}  // namespace twinrender::compare
