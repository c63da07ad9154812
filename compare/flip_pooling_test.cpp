#include "compare/flip_pooling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace twinrender::compare {
namespace {

core::Image map(int width, int height, const std::vector<float>& values) {
    core::Image m(width, height, {"flip"});
    std::copy(values.begin(), values.end(), m.pixels().begin());
    return m;
}

TEST(FlipPooling, PercentilesAndFractionOfARamp) {
    // 20 pixels 0, 0.05, ..., 0.95 (as floats). Sorted positions (numpy's linear method):
    // p95 at 0.95 * 19 = 18.05, between 0.90 and 0.95: 0.90 + 0.05 * 0.05 = 0.9025; p99 at
    // 18.81: 0.90 + 0.81 * 0.05 = 0.9405. Above 0.5: 0.55 ... 0.95, 9 of 20 = 0.45 (0.5 itself
    // is not above).
    std::vector<float> ramp;
    for (int i = 0; i < 20; ++i) ramp.push_back(static_cast<float>(i) * 0.05f);
    const FlipPooled p = poolFlip(map(4, 5, ramp));
    EXPECT_NEAR(p.p95, 0.9025, 1e-6);
    EXPECT_NEAR(p.p99, 0.9405, 1e-6);
    EXPECT_DOUBLE_EQ(p.over, 0.45);
    FlipPoolingSettings low;
    low.overLevel = 0.12;  // above it: 0.15 ... 0.95, 17 of 20
    EXPECT_DOUBLE_EQ(poolFlip(map(4, 5, ramp), low).over, 0.85);
}

TEST(FlipPooling, RareLargeErrorsThatTheMeanHides) {
    // 100 pixels, 98 of them 0 and two 1: mean 0.02, p95 (position 94.05) 0, p99 (position
    // 98.01, between the two ones) 1, 2 % of the pixels above 0.5.
    std::vector<float> v(100, 0.0f);
    v[17] = v[63] = 1.0f;
    const FlipPooled p = poolFlip(map(10, 10, v));
    EXPECT_EQ(p.p95, 0.0);
    EXPECT_EQ(p.p99, 1.0);
    EXPECT_DOUBLE_EQ(p.over, 0.02);
    // 200 pixels with one 1: p99 at 0.99 * 199 = 197.01 is still 0; over is 0.5 %.
    std::vector<float> w(200, 0.0f);
    w[5] = 1.0f;
    const FlipPooled q = poolFlip(map(20, 10, w));
    EXPECT_EQ(q.p99, 0.0);
    EXPECT_DOUBLE_EQ(q.over, 0.005);
}

TEST(FlipPooling, OnePixelAndNone) {
    const FlipPooled one = poolFlip(map(1, 1, {0.7f}));
    EXPECT_NEAR(one.p95, 0.7, 1e-7);
    EXPECT_NEAR(one.p99, 0.7, 1e-7);
    EXPECT_EQ(one.over, 1.0);
    const FlipPooled none = poolFlip(core::Image(0, 0, {"flip"}));
    EXPECT_TRUE(std::isnan(none.p95) && std::isnan(none.p99) && std::isnan(none.over));
}

TEST(FlipPooling, LevelOutsideZeroOneAndManyChannelsAreRejected) {
    for (double level : {0.0, 1.0, -0.1, std::nan("")}) {
        FlipPoolingSettings s;
        s.overLevel = level;
        EXPECT_THROW(poolFlip(map(1, 1, {0.5f}), s), std::invalid_argument) << level;
    }
    EXPECT_THROW(poolFlip(core::Image(2, 2, {"R", "G"})), std::invalid_argument);
}

}  // namespace
}  // namespace twinrender::compare
