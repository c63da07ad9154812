#include "compare/metric_table.h"

#include <gtest/gtest.h>

namespace twinrender::compare {
namespace {

TEST(MetricTable, Units) {
    EXPECT_EQ(metricUnit("beauty.psnr"), "dB");
    EXPECT_EQ(metricUnit("normal.mean_deg"), "°");
    EXPECT_EQ(metricUnit("silhouette.mean_px"), "px");
    EXPECT_EQ(metricUnit("time.realtime_ms"), "ms");
    EXPECT_EQ(metricUnit("beauty.ssim"), "");
}

}  // namespace
}  // namespace twinrender::compare
