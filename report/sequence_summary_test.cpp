#include "report/sequence_summary.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace twinrender::report {
namespace {

using namespace twinrender::compare;  // what the report shows

TEST(SequenceSummary, EachMetricAtItsWorstFrameTimesAtTheMedianFlickerPooled) {
    const std::vector<SequenceFrame> frames = {
        {3,
         {{"beauty.flip", 0.02},
          {"beauty.ssim", 0.95},
          {"smoothness.ratio", 0.9},
          {"time.realtime_ms", 100.0},
          {"uv.mean", NAN}},
         {}},
        {4,
         {{"beauty.flip", 0.05},
          {"beauty.ssim", 0.90},
          {"smoothness.ratio", 1.05},
          {"time.realtime_ms", 300.0},
          {"temporal.flicker", 0.01},
          {"temporal.frame_flip", 0.2},
          {"temporal.normal_flicker_deg", -1.0}},
         {}},
        {5,
         {{"beauty.flip", 0.03},
          {"beauty.ssim", 0.97},
          {"smoothness.ratio", 1.0},
          {"time.realtime_ms", 200.0},
          {"temporal.flicker", 0.03},
          {"temporal.frame_flip", 0.1},
          {"temporal.normal_flicker_deg", 2.0}},
         {}},
    };
    const MetricValues m = summariseSequence(frames);
    EXPECT_DOUBLE_EQ(m.at("beauty.flip"), 0.05);        // lower is better: the largest
    EXPECT_DOUBLE_EQ(m.at("beauty.ssim"), 0.90);        // higher is better: the smallest
    EXPECT_DOUBLE_EQ(m.at("smoothness.ratio"), 0.9);    // closest to 1: the farthest
    EXPECT_DOUBLE_EQ(m.at("time.realtime_ms"), 200.0);  // the median frame
    EXPECT_TRUE(std::isnan(m.at("uv.mean")));
    EXPECT_DOUBLE_EQ(m.at("temporal.flicker_mean"), 0.02);
    EXPECT_DOUBLE_EQ(m.at("temporal.flicker_max"), 0.03);
    EXPECT_DOUBLE_EQ(m.at("temporal.normal_flicker_mean_deg"), 0.5);
    EXPECT_DOUBLE_EQ(m.at("temporal.normal_flicker_max_deg"), 2.0);
    EXPECT_FALSE(m.count("temporal.flicker"));
    EXPECT_FALSE(m.count("temporal.frame_flip"));
    // The pooled keys, as `sweep --metric` accepts them on a sequence scene: exactly the
    // temporal ones the summary has.
    std::vector<std::string> temporal;
    for (const auto& [k, v] : m)
        if (k.starts_with("temporal.")) temporal.push_back(k);
    std::vector<std::string> pooled = pooledTemporalMetrics();
    std::sort(pooled.begin(), pooled.end());
    EXPECT_EQ(temporal, pooled);
    EXPECT_EQ(worstFrame(frames), 4);
    EXPECT_EQ(worstFrame({}), 0);
}

}  // namespace
}  // namespace twinrender::report
