#include "compare/ssim.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "compare/testdata/constant_image.h"
#include "compare/testdata/test_pairs.h"
#include "core/error.h"

namespace twinrender::compare {
namespace {

using testdata::constant;

TEST(Ssim, IdenticalImagesGiveExactlyOne) {
    const auto pair = testdata::gradientNoise();
    const SsimResult r = ssim(pair.test, pair.test);
    EXPECT_EQ(r.ssim, 1.0);
    for (double c : r.channelSsim) EXPECT_EQ(c, 1.0);
    ASSERT_TRUE(r.ssimMap.has_value());
    for (float v : r.ssimMap->pixels()) ASSERT_EQ(v, 1.0f);
}

TEST(Ssim, ConstantImagesLeaveOnlyTheLuminanceTerm) {
    // No variance: SSIM = (2 mu_x mu_y + C1) / (mu_x^2 + mu_y^2 + C1), C1 = (0.01)^2.
    const double C1 = 1e-4;
    auto expected = [&](double a, double b) { return (2 * a * b + C1) / (a * a + b * b + C1); };
    const SsimResult r =
        ssim(constant(20, 16, 0.5f, 0.25f, 0.0f), constant(20, 16, 0.75f, 0.25f, 1.0f));
    EXPECT_NEAR(r.channelSsim[0], expected(0.5, 0.75), 1e-6);
    EXPECT_NEAR(r.channelSsim[1], 1.0, 1e-6);
    EXPECT_NEAR(r.channelSsim[2], expected(0.0, 1.0), 1e-9);  // C1 / (1 + C1)
    EXPECT_NEAR(r.ssim, (expected(0.5, 0.75) + 1.0 + expected(0.0, 1.0)) / 3.0, 1e-6);
}

TEST(Ssim, MapIsTheChannelMeanAndItsCroppedMeanIsTheScore) {
    const auto pair = testdata::discBlur();
    const SsimResult r = ssim(pair.reference, pair.test);
    ASSERT_TRUE(r.ssimMap.has_value());
    const core::Image& map = *r.ssimMap;
    ASSERT_EQ(map.channelNames(), std::vector<std::string>{"ssim"});
    ASSERT_EQ(map.width(), pair.reference.width());
    ASSERT_EQ(map.height(), pair.reference.height());
    // scikit-image leaves out a border of (11 - 1) / 2 = 5 pixels.
    double sum = 0.0;
    for (int y = 5; y < map.height() - 5; ++y)
        for (int x = 5; x < map.width() - 5; ++x) sum += map.at(x, y, 0);
    EXPECT_NEAR(sum / ((map.width() - 10) * (map.height() - 10)), r.ssim, 1e-6);
    // Far from the disc both images are the same flat background.
    EXPECT_NEAR(map.at(2, 2, 0), 1.0f, 1e-6);
    EXPECT_LT(map.at(48, 13, 0), 0.9f);  // on the disc's blurred edge

    SsimSettings noMap;
    noMap.ssimMap = false;
    const SsimResult without = ssim(pair.reference, pair.test, noMap);
    EXPECT_FALSE(without.ssimMap.has_value());
    EXPECT_EQ(without.ssim, r.ssim);
}

TEST(Ssim, IgnoresOtherChannelsAndTheirOrder) {
    const auto pair = testdata::discBlur();
    const SsimResult plain = ssim(pair.reference, pair.test);
    const SsimResult aov = ssim(testdata::withOtherChannels(pair.reference), pair.test);
    EXPECT_EQ(plain.ssim, aov.ssim);
    EXPECT_EQ(*plain.ssimMap, *aov.ssimMap);
}

TEST(Ssim, IsSymmetric) {
    const auto pair = testdata::checkerShift();
    EXPECT_NEAR(ssim(pair.reference, pair.test).ssim, ssim(pair.test, pair.reference).ssim, 1e-7);
}

TEST(Ssim, SameResultOnOneThread) {
    const auto pair = testdata::gradientNoise();
    const SsimResult many = ssim(pair.reference, pair.test);
    tbb::task_arena one(1);
    const SsimResult single = one.execute([&] { return ssim(pair.reference, pair.test); });
    EXPECT_EQ(many.ssim, single.ssim);
    EXPECT_EQ(*many.ssimMap, *single.ssimMap);
}

TEST(Ssim, ImagesSmallerThanTheWindowAreRefused) {
    EXPECT_THROW(ssim(constant(10, 40, 0, 0, 0), constant(10, 40, 0, 0, 0)),
                 core::NotComparableError);
    EXPECT_NO_THROW(ssim(constant(11, 11, 0, 0, 0), constant(11, 11, 0, 0, 0)));
}

TEST(Ssim, DifferentSizesAreNotComparableAndTheMessageNamesBoth) {
    try {
        ssim(constant(97, 71, 0, 0, 0), constant(50, 40, 0, 0, 0));
        FAIL() << "expected NotComparableError";
    } catch (const core::NotComparableError& e) {
        EXPECT_NE(std::string(e.what()).find("97x71"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("50x40"), std::string::npos) << e.what();
    }
}

TEST(Ssim, MissingChannelIsNotComparable) {
    core::Image noBlue(16, 16, {"R", "G"});
    EXPECT_THROW(ssim(constant(16, 16, 0, 0, 0), noBlue), core::NotComparableError);
}

// Reference: scikit-image 0.19.3 (Debian 12 python3-skimage), numpy 1.24.2, on the PNGs that
// ReferencePairs.WriteForReferenceTools writes, read as uint8 and divided by 255 (float64):
//   skimage.metrics.structural_similarity(ref, test, channel_axis=2, gaussian_weights=True,
//       sigma=1.5, use_sample_covariance=False, data_range=1.0)
// (compare/testdata/reference_values.py prints them, 8 decimals). We agree to 1e-8; the
// tolerance is 1e-3.
TEST(Ssim, MatchesScikitImage) {
    const struct {
        const char* pair;
        double ssim;
    } expected[] = {
        {"gradient_noise", 0.27544400}, {"checker_shift", 0.22381297}, {"disc_blur", 0.91026907},
        {"colour_shift", 0.95920985},   {"dark_noise", 0.67661456},    {"black_white", 0.00009999},
    };
    for (const auto& e : expected) {
        const auto pair = testdata::referencePair(e.pair);
        EXPECT_NEAR(ssim(pair.reference, pair.test).ssim, e.ssim, 1e-3) << e.pair;
    }
}

}  // namespace
}  // namespace twinrender::compare
