#include "realtime/blue_noise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace tr = twinrender::realtime;

namespace {

// The energy of a side x side pattern's spectrum at the lowest frequencies (|k| <= 2, k != 0),
// relative to its total: about 12 / (side^2 - 1) for white noise, far less for blue noise.
double lowFrequencyShare(const std::vector<float>& v, int side) {
    double mean = 0.0;
    for (float x : v) mean += x;
    mean /= double(v.size());
    double low = 0.0, total = 0.0;
    for (int ky = -side / 2; ky < side / 2; ++ky)
        for (int kx = -side / 2; kx < side / 2; ++kx) {
            if (kx == 0 && ky == 0) continue;
            double re = 0.0, im = 0.0;
            for (int y = 0; y < side; ++y)
                for (int x = 0; x < side; ++x) {
                    const double a = 2.0 * std::numbers::pi * (kx * x + ky * y) / side;
                    const double d = v[std::size_t(y) * side + x] - mean;
                    re += d * std::cos(a);
                    im += d * std::sin(a);
                }
            const double power = re * re + im * im;
            total += power;
            if (kx * kx + ky * ky <= 4) low += power;
        }
    return low / total;
}

}  // namespace

TEST(BlueNoise, RanksEveryPixelOnceAndIsTheSameEachTime) {
    const int side = 16;
    const std::vector<float> a = tr::blueNoise(side), b = tr::blueNoise(side);
    ASSERT_EQ(a.size(), 256u);
    EXPECT_EQ(a, b);
    std::vector<float> sorted = a;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t k = 0; k < sorted.size(); ++k)
        ASSERT_FLOAT_EQ(sorted[k], float((k + 0.5) / 256.0));
    EXPECT_THROW(tr::blueNoise(2), std::invalid_argument);
}

TEST(BlueNoise, HasLittleEnergyAtLowFrequencies) {
    // 12 of the 1023 non-zero frequencies of a 32 x 32 tile have |k| <= 2: white noise puts about
    // 1.2 % of its energy there. Void-and-cluster pushes it to high frequencies: measured 0.02 %;
    // a pattern with a tenth of white noise's low-frequency share would already be blue.
    const int side = 32;
    const std::vector<float> blue = tr::blueNoise(side);
    std::vector<float> white(blue.size());
    std::uint32_t state = 7u;
    for (float& w : white) {
        state = state * 1664525u + 1013904223u;
        w = float(state >> 8) / 16777216.0f;
    }
    const double whiteShare = lowFrequencyShare(white, side);
    EXPECT_GT(whiteShare, 0.004);
    EXPECT_LT(lowFrequencyShare(blue, side), 0.1 * whiteShare);
}
