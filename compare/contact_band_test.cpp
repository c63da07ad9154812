#include "compare/contact_band.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/frame.h"

namespace tc = twinrender::compare;
namespace core = twinrender::core;

namespace {

// A 10 x 3 strip: body 0 on x < 5, body 1 on x >= 5, u = 0.1 everywhere, no emission.
core::Image strip() {
    core::Image img = core::aov::makeImage(10, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 10; ++x) {
            img.at(x, y, img.channelIndex("A")) = 1.0f;
            img.at(x, y, img.channelIndex("Z")) = 5.0f;
            img.at(x, y, img.channelIndex("N.Z")) = 1.0f;
            img.at(x, y, img.channelIndex("uv.U")) = 0.1f;
            img.at(x, y, img.channelIndex("id")) = x < 5 ? 0.0f : 1.0f;
        }
    return img;
}

}  // namespace

TEST(ContactBand, PixelsWithinTheRadiusOfAnotherBody) {
    const core::Image ref = strip();
    const tc::Masks masks = tc::computeMasks(ref, ref);
    // Radius 2: columns 3, 4 (body 0) and 5, 6 (body 1) on every row.
    const tc::Mask band = tc::contactBandMask(ref, masks, 2);
    EXPECT_EQ(band.count(), 4u * 3u);
    for (int x = 0; x < 10; ++x) EXPECT_EQ(band(x, 1), x >= 3 && x <= 6) << x;
    EXPECT_THROW(tc::contactBandMask(ref, masks, 0), std::invalid_argument);
}

TEST(ContactBand, UvAndEmissionBleedingOnTheBandOnly) {
    const core::Image ref = strip();
    core::Image test = strip();
    // Body 1's uv (0.3) bled into column 4, body 0's emission (2, 0, 0) into column 5, and an
    // error far from the contact (column 0) that the band does not see.
    for (int y = 0; y < 3; ++y) {
        test.at(4, y, test.channelIndex("uv.U")) = 0.3f;
        test.at(5, y, test.channelIndex("emission.R")) = 2.0f;
        test.at(0, y, test.channelIndex("uv.U")) = 0.9f;
    }
    const tc::Masks masks = tc::computeMasks(ref, test);
    const auto r = tc::contactBandError(ref, test, masks, 2);
    ASSERT_EQ(r.pixels, 12u);
    // uv: 3 of 12 band pixels off by 0.2 -> 0.05. Emission: 3 pixels with R off by 2 ->
    // sqrt(3 * 4 / (12 * 3)) = sqrt(1/3).
    EXPECT_NEAR(r.uvMean, 0.05, 1e-6);
    EXPECT_NEAR(r.emissionRmse, std::sqrt(1.0 / 3.0), 1e-6);
}

TEST(ContactBand, OneBodyHasNoBand) {
    core::Image ref = strip();
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 10; ++x) ref.at(x, y, ref.channelIndex("id")) = 0.0f;
    const auto r = tc::contactBandError(ref, ref, tc::computeMasks(ref, ref), 3);
    EXPECT_EQ(r.pixels, 0u);
    EXPECT_TRUE(std::isnan(r.uvMean));
    EXPECT_TRUE(std::isnan(r.emissionRmse));
}
