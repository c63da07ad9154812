#include "compare/colour_map.h"

#include <gtest/gtest.h>

#include <cmath>

namespace twinrender::compare {
namespace {

TEST(ColourMap, MagmaRunsFromBlackToPaleYellow) {
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

}  // namespace
}  // namespace twinrender::compare
