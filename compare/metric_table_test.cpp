#include "compare/metric_table.h"

#include <gtest/gtest.h>

#include <cctype>
#include <set>

#include "compare/metrics.h"
#include "compare/testdata/synthetic_aov.h"

namespace twinrender::compare {
namespace {

std::set<std::string> keysOf(const MetricResult& r) {
    std::set<std::string> keys;
    for (const auto& [k, v] : r.values) keys.insert(k);
    return keys;
}

MetricResult aovPair() {
    return computeMetrics(testdata::syntheticAov(32, 20, 16.0, 10.0, 8.0),
                          testdata::syntheticAov(32, 20, 17.0, 10.0, 8.5));
}

MetricResult plainPair() {
    const std::vector<std::string> rgb = {"R", "G", "B"};
    return computeMetrics(testdata::syntheticAov(32, 20, 16.0, 10.0, 8.0).select(rgb),
                          testdata::syntheticAov(32, 20, 17.0, 10.0, 8.5).select(rgb));
}

TEST(MetricTable, EveryKeyTheMetricsWriteIsInTheTable) {
    for (const MetricResult& r : {aovPair(), plainPair()})
        for (const std::string& key : keysOf(r)) {
            const MetricInfo* m = findMetric(key);
            ASSERT_NE(m, nullptr) << key;
            EXPECT_TRUE(m->source == MetricSource::AnyPair || m->source == MetricSource::AovPair)
                << key;
        }
    for (const std::string& key : keysOf(plainPair()))
        EXPECT_TRUE(computedOnPlainImages(key)) << key;
}

// The entries of the other sources are written elsewhere, when they apply: the times and the
// counters by the commands that render (time.<renderer>_ms, count.<counter>), occlusion.error,
// contact.* and temporal.* by the studies that ask for them (app/studies.h).
TEST(MetricTable, EveryComparisonEntryIsWrittenOnAFullAovPair) {
    const std::set<std::string> aov = keysOf(aovPair()), plain = keysOf(plainPair());
    for (const MetricInfo& m : metricTable()) {
        const std::string key(m.key);
        if (m.source == MetricSource::AnyPair) {
            EXPECT_TRUE(aov.count(key)) << key;
            EXPECT_TRUE(plain.count(key)) << key;
        } else if (m.source == MetricSource::AovPair) {
            EXPECT_TRUE(aov.count(key)) << key;
            EXPECT_FALSE(plain.count(key)) << key;
        } else {
            EXPECT_FALSE(aov.count(key)) << key;
        }
    }
}

TEST(MetricTable, KeysAreUniqueDottedSnakeCaseWithAMeaning) {
    std::set<std::string_view> seen;
    for (const MetricInfo& m : metricTable()) {
        EXPECT_TRUE(seen.insert(m.key).second) << m.key;
        EXPECT_NE(m.key.find('.'), std::string_view::npos) << m.key;
        for (char c : m.key)
            EXPECT_TRUE(std::islower(static_cast<unsigned char>(c)) || std::isdigit(c) ||
                        c == '.' || c == '_' || c == '<' || c == '>')
                << m.key;
        EXPECT_FALSE(m.meaning.empty()) << m.key;
        EXPECT_GT(m.noise, 0.0) << m.key;
        EXPECT_EQ(findMetric(m.key), &m) << m.key;
    }
}

TEST(MetricTable, FamiliesTakeEveryMemberAndNothingElse) {
    ASSERT_NE(findMetric("time.realtime_ms"), nullptr);
    EXPECT_EQ(findMetric("time.realtime_ms")->key, "time.<renderer>_ms");
    EXPECT_EQ(findMetric("time.raymarch_ms"), findMetric("time.realtime_ms"));
    EXPECT_EQ(findMetric("time.mine_ms"), findMetric("time.realtime_ms"));  // a third renderer
    EXPECT_EQ(findMetric("time._ms"), nullptr);
    EXPECT_EQ(findMetric("time.realtime"), nullptr);
    ASSERT_NE(findMetric("count.unbracketed_rays"), nullptr);
    EXPECT_EQ(findMetric("count.unbracketed_rays")->key, "count.<counter>");
    EXPECT_EQ(findMetric("count."), nullptr);
    EXPECT_EQ(findMetric("beauty.flop"), nullptr);
    EXPECT_EQ(findMetric("beauty"), nullptr);
}

TEST(MetricTable, Units) {
    EXPECT_EQ(metricUnit("beauty.psnr"), "dB");
    EXPECT_EQ(metricUnit("normal.mean_deg"), "°");
    EXPECT_EQ(metricUnit("silhouette.mean_px"), "px");
    EXPECT_EQ(metricUnit("time.realtime_ms"), "ms");
    EXPECT_EQ(metricUnit("beauty.ssim"), "");
    EXPECT_EQ(metricUnit("no.such_metric"), "");
}

TEST(MetricTable, DisplayOrderIsTheTablesFamiliesByNameUnknownLast) {
    EXPECT_EQ(inMetricOrder({"zz.unknown", "time.realtime_ms", "shadow.iou", "time.raymarch_ms",
                             "beauty.flip", "count.segments", "beauty.psnr", "aa.unknown"}),
              (std::vector<std::string>{"beauty.psnr", "beauty.flip", "shadow.iou",
                                        "time.raymarch_ms", "time.realtime_ms", "count.segments",
                                        "aa.unknown", "zz.unknown"}));
    EXPECT_TRUE(metricLess("normal.mean_deg", "normal.p95_deg"));
    EXPECT_FALSE(metricLess("beauty.flip", "beauty.flip"));
}

TEST(MetricTable, NamesForMessages) {
    const std::string all = metricNames();
    EXPECT_EQ(all.rfind("beauty.psnr, beauty.ssim, beauty.flip, ", 0), 0u) << all;
    EXPECT_NE(all.find("time.<renderer>_ms"), std::string::npos) << all;
    const std::string computed = metricNames(true);
    EXPECT_NE(computed.find("shadow.missed_shadow"), std::string::npos) << computed;
    EXPECT_EQ(computed.find("occlusion.error"), std::string::npos) << computed;
    EXPECT_TRUE(computedByComparison("coverage.iou"));
    EXPECT_FALSE(computedByComparison("time.realtime_ms"));
    EXPECT_FALSE(computedOnPlainImages("coverage.iou"));
}

}  // namespace
}  // namespace twinrender::compare
