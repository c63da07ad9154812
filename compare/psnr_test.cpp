#include "compare/psnr.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include "compare/testdata/constant_image.h"
#include "compare/testdata/test_pairs.h"
#include "core/error.h"
#include "core/image_io.h"
#include "tests/scratch_dir.h"

namespace twinrender::compare {
namespace {

using testdata::constant;

TEST(Psnr, ConstantOffsetOfOneTenthIs20Decibels) {
    // MSE = 0.1^2 = 0.01, PSNR = 10 log10(1 / 0.01) = 20 dB. 0.6f - 0.5f is 0.1 + 2.4e-8,
    // hence the tolerance.
    const PsnrResult r =
        psnr(constant(40, 30, 0.5f, 0.5f, 0.5f), constant(40, 30, 0.6f, 0.6f, 0.6f));
    EXPECT_NEAR(r.mse, 0.01, 1e-8);
    EXPECT_NEAR(r.psnr, 20.0, 1e-5);
}

TEST(Psnr, OneChannelOffsetCountsAsOneThirdOfTheError) {
    // Only R differs by 0.125 (exact in float): MSE = 0.125^2 / 3, PSNR = 20 log10(8) +
    // 10 log10(3) = 18.0618 + 4.7712 dB.
    const PsnrResult r = psnr(constant(8, 8, 0.5f, 0.2f, 0.3f), constant(8, 8, 0.625f, 0.2f, 0.3f));
    EXPECT_DOUBLE_EQ(r.channelMse[0], 0.125 * 0.125);
    EXPECT_DOUBLE_EQ(r.channelMse[1], 0.0);
    EXPECT_DOUBLE_EQ(r.channelMse[2], 0.0);
    EXPECT_NEAR(r.psnr, 20.0 * std::log10(8.0) + 10.0 * std::log10(3.0), 1e-12);
}

TEST(Psnr, PeakScalesTheRatio) {
    PsnrSettings settings;
    settings.peak = 2.0;  // 20 log10(2) = 6.0206 dB more
    const PsnrResult one =
        psnr(constant(8, 8, 0.5f, 0.5f, 0.5f), constant(8, 8, 0.625f, 0.5f, 0.5f));
    const PsnrResult two =
        psnr(constant(8, 8, 0.5f, 0.5f, 0.5f), constant(8, 8, 0.625f, 0.5f, 0.5f), settings);
    EXPECT_NEAR(two.psnr - one.psnr, 20.0 * std::log10(2.0), 1e-12);
}

TEST(Psnr, IdenticalImagesGiveInfinity) {
    const auto pair = testdata::gradientNoise();
    const PsnrResult r = psnr(pair.test, pair.test);
    EXPECT_EQ(r.mse, 0.0);
    EXPECT_EQ(r.psnr, std::numeric_limits<double>::infinity());
}

TEST(Psnr, ErrorMapHoldsTheMeanSquaredErrorOfEachPixel) {
    const auto pair = testdata::discBlur();
    PsnrSettings settings;
    EXPECT_FALSE(psnr(pair.reference, pair.test, settings).errorMap.has_value());
    settings.errorMap = true;
    const PsnrResult r = psnr(pair.reference, pair.test, settings);
    ASSERT_TRUE(r.errorMap.has_value());
    ASSERT_EQ(r.errorMap->channelNames(), std::vector<std::string>{"squared_error"});
    ASSERT_EQ(r.errorMap->width(), pair.reference.width());
    double sum = 0.0;
    for (float v : r.errorMap->pixels()) sum += v;
    EXPECT_NEAR(sum / static_cast<double>(r.errorMap->pixelCount()), r.mse, 1e-7);
    const float d = pair.reference.at(30, 20, 0) - pair.test.at(30, 20, 0);
    const float e = pair.reference.at(30, 20, 1) - pair.test.at(30, 20, 1);
    const float f = pair.reference.at(30, 20, 2) - pair.test.at(30, 20, 2);
    EXPECT_NEAR(r.errorMap->at(30, 20, 0), (d * d + e * e + f * f) / 3.0f, 1e-7);
}

TEST(Psnr, IgnoresOtherChannelsAndTheirOrder) {
    const auto pair = testdata::gradientNoise();
    EXPECT_EQ(psnr(pair.reference, testdata::withOtherChannels(pair.test)).psnr,
              psnr(pair.reference, pair.test).psnr);
}

TEST(Psnr, DifferentSizesAreNotComparableAndTheMessageNamesBoth) {
    try {
        psnr(constant(97, 71, 0, 0, 0), constant(50, 40, 0, 0, 0));
        FAIL() << "expected NotComparableError";
    } catch (const core::NotComparableError& e) {
        EXPECT_NE(std::string(e.what()).find("97x71"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("50x40"), std::string::npos) << e.what();
    }
}

TEST(Psnr, MissingChannelIsNotComparable) {
    core::Image grey(8, 8, {"Y"});
    EXPECT_THROW(psnr(constant(8, 8, 0, 0, 0), grey), core::NotComparableError);
}

TEST(Psnr, SameResultOnOneThread) {
    const auto pair = testdata::checkerShift();
    const PsnrResult many = psnr(pair.reference, pair.test);
    tbb::task_arena one(1);
    const PsnrResult single = one.execute([&] { return psnr(pair.reference, pair.test); });
    EXPECT_EQ(many.psnr, single.psnr);
}

// Reference: scikit-image 0.19.3 (Debian 12 python3-skimage), numpy 1.24.2, on the PNGs that
// ReferencePairs.WriteForReferenceTools writes, read as uint8 and divided by 255:
//   skimage.metrics.peak_signal_noise_ratio(ref, test, data_range=1.0)
// (compare/testdata/reference_values.py prints them). dB, printed with 6 decimals; our
// values agree to 1e-6, the tolerance is 1e-3.
TEST(Psnr, MatchesScikitImage) {
    const struct {
        const char* pair;
        double psnr;
    } expected[] = {
        {"gradient_noise", 24.790596}, {"checker_shift", 9.293021}, {"disc_blur", 25.278291},
        {"colour_shift", 20.992186},   {"dark_noise", 33.626347},   {"black_white", 0.000000},
    };
    for (const auto& e : expected) {
        const auto pair = testdata::referencePair(e.pair);
        EXPECT_NEAR(psnr(pair.reference, pair.test).psnr, e.psnr, 1e-3) << e.pair;
    }
}

// Writes the test pairs as 8-bit PNGs into `dir` and reads them back: the PNGs hold the pixels
// the tests use, 8-bit values k with k / 255 our value (the reader's conversion may differ from
// k / 255.0f in the last bit).
void writeReferencePairs(const std::filesystem::path& dir) {
    std::filesystem::create_directories(dir);
    for (const auto& pair : testdata::referencePairs()) {
        core::writeImage(pair.reference, dir / (pair.name + ".ref.png"));
        core::writeImage(pair.test, dir / (pair.name + ".test.png"));
        for (const char* which : {".ref.png", ".test.png"}) {
            const core::Image& ours = which[1] == 'r' ? pair.reference : pair.test;
            const core::Image read = core::readImage(dir / (pair.name + which));
            ASSERT_EQ(read.width(), ours.width());
            ASSERT_EQ(read.height(), ours.height());
            for (std::size_t p = 0; p < ours.pixelCount(); ++p)
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(read.at(p, read.requireChannel(ours.channelNames()[c])),
                                ours.at(p, c), 1e-6f)
                        << pair.name << which;
        }
    }
}

// The writer of the test below, into the build tree's scratch folder, so that its round trip
// runs on every test run.
TEST(ReferencePairs, RoundTripThroughTheirPngs) {
    writeReferencePairs(twinrender::testing::freshDir("reference_pairs"));
}

// Writes the test pairs as 8-bit PNGs for the reference tools (skimage, NVlabs' flip) when
// TWINRENDER_WRITE_TEST_PAIRS names a folder; skipped otherwise. See
// compare/testdata/reference_values.py.
TEST(ReferencePairs, WriteForReferenceTools) {
    const char* dir = std::getenv("TWINRENDER_WRITE_TEST_PAIRS");
    if (!dir) GTEST_SKIP() << "set TWINRENDER_WRITE_TEST_PAIRS=DIR to write the test pairs";
    writeReferencePairs(dir);
}

}  // namespace
}  // namespace twinrender::compare
