#include "compare/distance_transform.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace twinrender::compare {
namespace {

// Squared distance to the nearest feature by trying every feature: the definition, O(n^2).
std::vector<float> bruteForce(const Mask& features) {
    const int w = features.width(), h = features.height();
    std::vector<float> d(features.pixelCount(), std::numeric_limits<float>::infinity());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int qy = 0; qy < h; ++qy)
                for (int qx = 0; qx < w; ++qx)
                    if (features(qx, qy)) {
                        const float d2 =
                            static_cast<float>((x - qx) * (x - qx) + (y - qy) * (y - qy));
                        d[static_cast<std::size_t>(y) * w + x] =
                            std::min(d[static_cast<std::size_t>(y) * w + x], d2);
                    }
    return d;
}

Mask randomMask(int w, int h, double density, std::uint32_t seed) {
    Mask m(w, h);
    std::uint32_t state = seed;
    for (std::size_t p = 0; p < m.pixelCount(); ++p) {
        state = 1664525u * state + 1013904223u;
        m.set(p, static_cast<double>(state >> 8) / 16777216.0 < density);
    }
    return m;
}

TEST(DistanceTransform, EmptyMaskIsInfiniteEverywhere) {
    for (float d : squaredDistanceTransform(Mask(13, 7)))
        ASSERT_EQ(d, std::numeric_limits<float>::infinity());
}

TEST(DistanceTransform, OnePixelGivesTheSquaredEuclideanDistance) {
    Mask m(9, 7);
    m.set(3, 2, true);
    const auto d = squaredDistanceTransform(m);
    for (int y = 0; y < 7; ++y)
        for (int x = 0; x < 9; ++x)
            EXPECT_EQ(d[static_cast<std::size_t>(y) * 9 + x],
                      (x - 3) * (x - 3) + (y - 2) * (y - 2));
}

TEST(DistanceTransform, EqualsBruteForceOnRandomMasks) {
    // Sparse masks make long envelopes, dense ones many ties; odd sizes catch off-by-ones.
    for (double density : {0.003, 0.02, 0.2, 0.7}) {
        const Mask m = randomMask(37, 23, density, 7u + static_cast<std::uint32_t>(density * 1000));
        EXPECT_EQ(squaredDistanceTransform(m), bruteForce(m)) << "density " << density;
    }
}

TEST(DistanceTransform, SingleRowAndColumn) {
    for (auto [w, h] : {std::pair{31, 1}, std::pair{1, 29}}) {
        const Mask m = randomMask(w, h, 0.1, 99u);
        EXPECT_EQ(squaredDistanceTransform(m), bruteForce(m)) << w << "x" << h;
    }
}

TEST(DistanceTransform, SameResultOnOneThread) {
    const Mask m = randomMask(301, 157, 0.01, 5u);
    const auto many = squaredDistanceTransform(m);
    tbb::task_arena one(1);
    EXPECT_EQ(one.execute([&] { return squaredDistanceTransform(m); }), many);
}

}  // namespace
}  // namespace twinrender::compare
