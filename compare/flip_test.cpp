#include "compare/flip.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <stdexcept>

#include "compare/testdata/constant_image.h"
#include "compare/testdata/test_pairs.h"
#include "core/error.h"

namespace twinrender::compare {
namespace {

using testdata::constant;

TEST(Flip, IdenticalImagesGiveExactlyZero) {
    for (const auto& pair : testdata::referencePairs()) {
        const FlipResult r = flip(pair.test, pair.test);
        EXPECT_EQ(r.mean, 0.0) << pair.name;
        for (float v : r.errorMap.pixels()) ASSERT_EQ(v, 0.0f) << pair.name;
    }
}

TEST(Flip, ErrorMapIsOneChannelInZeroOne) {
    const auto pair = testdata::checkerShift();
    const FlipResult r = flip(pair.reference, pair.test);
    ASSERT_EQ(r.errorMap.channelNames(), std::vector<std::string>{"flip"});
    ASSERT_EQ(r.errorMap.width(), pair.reference.width());
    ASSERT_EQ(r.errorMap.height(), pair.reference.height());
    double sum = 0.0;
    for (float v : r.errorMap.pixels()) {
        ASSERT_GE(v, 0.0f);
        ASSERT_LE(v, 1.0f);
        sum += v;
    }
    EXPECT_NEAR(sum / static_cast<double>(r.errorMap.pixelCount()), r.mean, 1e-9);
}

TEST(Flip, IgnoresOtherChannelsAndTheirOrder) {
    const auto pair = testdata::colourShift();
    const FlipResult plain = flip(pair.reference, pair.test);
    const FlipResult aov = flip(pair.reference, testdata::withOtherChannels(pair.test));
    EXPECT_EQ(plain.mean, aov.mean);
    EXPECT_EQ(plain.errorMap, aov.errorMap);
}

TEST(Flip, ValuesOutsideZeroOneAreClamped) {
    const FlipResult r =
        flip(constant(32, 32, 1.0f, 0.0f, 0.5f), constant(32, 32, 1.5f, -0.25f, 0.5f));
    EXPECT_EQ(r.mean, 0.0);
}

TEST(Flip, SameResultOnOneThread) {
    const auto pair = testdata::discBlur();
    const FlipResult many = flip(pair.reference, pair.test);
    tbb::task_arena one(1);
    const FlipResult single = one.execute([&] { return flip(pair.reference, pair.test); });
    EXPECT_EQ(many.mean, single.mean);
    EXPECT_EQ(many.errorMap, single.errorMap);
}

TEST(Flip, DifferentSizesAreNotComparableAndTheMessageNamesBoth) {
    try {
        flip(constant(97, 71, 0, 0, 0), constant(50, 40, 0, 0, 0));
        FAIL() << "expected NotComparableError";
    } catch (const core::NotComparableError& e) {
        EXPECT_NE(std::string(e.what()).find("97x71"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("50x40"), std::string::npos) << e.what();
    }
}

TEST(Flip, MissingChannelIsNotComparable) {
    core::Image noGreen(16, 16, {"R", "B"});
    EXPECT_THROW(flip(constant(16, 16, 0, 0, 0), noGreen), core::NotComparableError);
}

TEST(Flip, NonPositivePpdIsRejected) {
    FlipSettings settings;
    settings.ppd = 0.0;
    EXPECT_THROW(flip(constant(8, 8, 0, 0, 0), constant(8, 8, 0, 0, 0), settings),
                 std::invalid_argument);
}

TEST(Flip, TinyImagesWork) {
    // Smaller than every filter: the clamped border covers the whole window.
    const FlipResult r = flip(constant(1, 1, 0, 0, 0), constant(1, 1, 1, 1, 1));
    EXPECT_NEAR(r.mean, 0.967387, 1e-4);  // black against white, as the black_white pair
}

// Reference: NVlabs' flip tool v1.6 (github.com/NVlabs/flip, commit 1eb247c, C++ tool built
// with g++ 12 -O2 -fopenmp), on the PNGs that ReferencePairs.WriteForReferenceTools writes:
//   flip -r NAME.ref.png -t NAME.test.png -ppd 67 -v 1      (and -ppd 30)
// (compare/testdata/reference_values.py builds the tool and prints them). The tool prints 6
// decimals. We agree with its error maps' means to 2e-6, except black_white: there the tool
// adds up its mean in float, which comes out 6.6e-5 low (its map is 0.967392 everywhere, ours
// 0.967387, the exact value 0.967380: on a uniform image the feature filters' float rounding,
// ~1e-9, is raised to qf = 0.5 and moves FLIP by ~1e-5 in both). Tolerance 1e-3.
TEST(Flip, MatchesNvlabsReferenceMeans) {
    const struct {
        const char* pair;
        double ppd67, ppd30;
    } expected[] = {
        {"gradient_noise", 0.117402, 0.233750}, {"checker_shift", 0.564236, 0.645361},
        {"disc_blur", 0.062652, 0.062490},      {"colour_shift", 0.283543, 0.280046},
        {"dark_noise", 0.021653, 0.042971},     {"black_white", 0.967321, 0.967321},
    };
    FlipSettings at30;
    at30.ppd = 30.0;
    for (const auto& e : expected) {
        const auto pair = testdata::referencePair(e.pair);
        EXPECT_NEAR(flip(pair.reference, pair.test).mean, e.ppd67, 1e-3) << e.pair;
        EXPECT_NEAR(flip(pair.reference, pair.test, at30).mean, e.ppd30, 1e-3) << e.pair;
    }
}

// Reference: FLIP::evaluate() of the same repository's src/cpp/FLIP.h at 67 ppd, on the same
// PNGs loaded as its tool loads them (the driver in compare/testdata/reference_values.py).
// Over whole maps the largest difference we saw was 6.1e-5 (checker_shift at (15, 14), on an
// edge where float rounding in the filters matters most); tolerance 2e-4.
TEST(Flip, MatchesNvlabsReferenceErrorMap) {
    const struct {
        const char* pair;
        int x, y;
        float flip;
    } expected[] = {
        {"checker_shift", 15, 14, 0.4585410f},  {"checker_shift", 48, 35, 0.8631881f},
        {"checker_shift", 0, 0, 0.1157401f},    {"disc_blur", 27, 35, 0.4945659f},
        {"disc_blur", 48, 13, 0.4435124f},      {"colour_shift", 96, 70, 0.6396316f},
        {"gradient_noise", 84, 60, 0.0684415f}, {"dark_noise", 10, 50, 0.0120081f},
    };
    for (const auto& e : expected) {
        const auto pair = testdata::referencePair(e.pair);
        const FlipResult r = flip(pair.reference, pair.test);
        EXPECT_NEAR(r.errorMap.at(e.x, e.y, 0), e.flip, 2e-4) << e.pair << " " << e.x << "," << e.y;
    }
}

}  // namespace
}  // namespace twinrender::compare
