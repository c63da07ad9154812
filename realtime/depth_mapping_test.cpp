#include "realtime/depth_mapping.h"

#include <gtest/gtest.h>

#include <cmath>

namespace twinrender::realtime {
namespace {

TEST(DepthMapping, LogDepthIsZeroAtTheEyeAndOneAtFar) {
    EXPECT_DOUBLE_EQ(logDepth(0.0, 0.05, 100.0), 0.0);
    EXPECT_DOUBLE_EQ(logDepth(100.0, 0.05, 100.0), 1.0);
    EXPECT_NEAR(logDepth(0.05, 0.05, 100.0), 1.0 / std::log2(1.0 + 100.0 / 0.05), 1e-15);
}

TEST(DepthMapping, EveryModeRoundTripsOverTenDecades) {
    const double near = 1e-3, far = 1e7;  // far / near = 1e10, the telescope scene's range
    for (DepthMode mode : {DepthMode::Standard, DepthMode::Log, DepthMode::Reversed}) {
        double previous = windowDepth(mode, near, near, far);
        for (double z = near; z <= far; z *= 1.7) {
            const double d = windowDepth(mode, z, near, far);
            EXPECT_GE(d, 0.0);
            EXPECT_LE(d, 1.0);
            EXPECT_NEAR(eyeDepth(mode, d, near, far) / z, 1.0, 1e-6)
                << toString(mode) << " z=" << z;
            if (z > near) {
                if (nearerIsLarger(mode))
                    EXPECT_LT(d, previous) << toString(mode);
                else
                    EXPECT_GT(d, previous) << toString(mode);
            }
            previous = d;
        }
    }
    EXPECT_DOUBLE_EQ(standardDepth(near, near, far), 0.0);
    EXPECT_DOUBLE_EQ(standardDepth(far, near, far), 1.0);
    EXPECT_DOUBLE_EQ(reversedDepth(near, near, far), 1.0);
    EXPECT_DOUBLE_EQ(reversedDepth(far, near, far), 0.0);
}

// What the log buffer is for: two surfaces 0.1 % apart stay distinct in a float depth buffer at
// every distance when far / near = 1e10, while the standard mapping merges them far away.
TEST(DepthMapping, LogKeepsRelativeOrderInFloatWhereStandardDoesNot) {
    const double near = 1e-3, far = 1e7;
    int standardMerged = 0;
    for (double z = 1e-2; z < far / 1.001; z *= 10.0) {
        const float a = static_cast<float>(logDepth(z, near, far));
        const float b = static_cast<float>(logDepth(z * 1.001, near, far));
        EXPECT_LT(a, b) << "log depth merges z=" << z;
        const float sa = static_cast<float>(standardDepth(z, near, far));
        const float sb = static_cast<float>(standardDepth(z * 1.001, near, far));
        if (!(sa < sb)) ++standardMerged;
    }
    EXPECT_GE(standardMerged, 3);
}

}  // namespace
}  // namespace twinrender::realtime
