#include "compare/hdr_flip.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "compare/flip.h"
#include "compare/testdata/test_pairs.h"
#include "core/image_io.h"
#include "tests/scratch_dir.h"

namespace twinrender::compare {
namespace {

using testdata::HEIGHT;
using testdata::WIDTH;

core::Image rgbImage(int width, int height) {
    return core::Image(width, height, {"R", "G", "B"});
}

void setGrey(core::Image& image, int x, int y, float v) {
    for (int c = 0; c < 3; ++c) image.at(x, y, c) = v;
}

// Particles on black space: a lit ball (radiance 0.05 to 1) with an emissive hot spot up to 24
// (a blackbody glow), on a black background that covers most of the image. The test's ball is
// one pixel to the right and its hot spot 20 % dimmer and wider.
struct HdrPair {
    std::string name;
    core::Image reference, test;
};

core::Image glowingBall(double cx, double cy, double radius, double peak, double spot) {
    core::Image img = rgbImage(WIDTH, HEIGHT);
    for (int y = 0; y < HEIGHT; ++y)
        for (int x = 0; x < WIDTH; ++x) {
            const double dx = (x + 0.5 - cx) / radius, dy = (y + 0.5 - cy) / radius;
            const double r2 = dx * dx + dy * dy;
            if (r2 >= 1.0) continue;
            const double lit =
                0.05 + 0.95 * std::max(0.0, -0.6 * dx - 0.5 * dy + 0.62 * std::sqrt(1.0 - r2));
            const double glow = peak * std::exp(-r2 / (spot * spot));
            img.at(x, y, 0) = static_cast<float>(lit * 0.9 + glow);
            img.at(x, y, 1) = static_cast<float>(lit * 0.7 + 0.45 * glow);
            img.at(x, y, 2) = static_cast<float>(lit * 0.6 + 0.1 * glow);
        }
    return img;
}

HdrPair glowOnBlack() {
    return {"glow_on_black", glowingBall(40.0, 35.0, 20.0, 24.0, 0.3),
            glowingBall(41.0, 35.0, 20.0, 19.2, 0.36)};
}

// No black pixel: a sky whose radiance spans 0.01 to 50 from left to right, and a test with
// noise of 10 % (fixed seed) and a dimmer sun disc.
HdrPair noisySky() {
    HdrPair p{"noisy_sky", rgbImage(WIDTH, HEIGHT), rgbImage(WIDTH, HEIGHT)};
    testdata::Lcg rng(7);
    for (int y = 0; y < HEIGHT; ++y)
        for (int x = 0; x < WIDTH; ++x) {
            const float sky = 0.01f * std::pow(5000.0f, static_cast<float>(x) / (WIDTH - 1));
            const float dx = static_cast<float>(x - 70), dy = static_cast<float>(y - 20);
            const bool sun = dx * dx + dy * dy < 36.0f;
            const float blue[3] = {0.6f, 0.8f, 1.0f};
            for (int c = 0; c < 3; ++c) {
                p.reference.at(x, y, c) = sun ? 400.0f : sky * blue[c];
                p.test.at(x, y, c) = sun ? 300.0f : sky * blue[c] * (0.9f + 0.2f * rng.next());
            }
        }
    return p;
}

TEST(HdrFlip, ExposureRangeOfParticlesOnBlackComesFromTheLitPixels) {
    // 15 pixels: 10 black, 3 of luminance 1, 2 of luminance 5. x_max, the radiance ACES maps to
    // 0.85, is the larger root of (a - 0.85 d) x^2 + (b - 0.85 e) x - 0.85 f: 2.11894 (by hand:
    // 0.160020 x^2 - 0.282900 x - 0.119 = 0). The lit pixels' upper median is 1, their maximum
    // 5: c_start = log2(2.11894 / 5) = -1.23860, c_stop = log2(2.11894) = 1.08333, and
    // ceil(2.32193) = 3 exposures. (Over every pixel the median is 0 and c_stop infinite.)
    core::Image img = rgbImage(5, 3);
    for (int x = 0; x < 3; ++x) setGrey(img, x, 1, 1.0f);
    setGrey(img, 3, 1, 5.0f);
    setGrey(img, 4, 2, 5.0f);
    const ExposureRange r = exposureRange(img);
    EXPECT_NEAR(r.start, -1.23860, 1e-4);
    EXPECT_NEAR(r.stop, 1.08333, 1e-4);
    EXPECT_EQ(r.count, 3);
    // All black: one exposure, 0, twice.
    const ExposureRange black = exposureRange(rgbImage(4, 4));
    EXPECT_EQ(black.start, 0.0);
    EXPECT_EQ(black.stop, 0.0);
    EXPECT_EQ(black.count, 2);
    // The paper's count: ceil(stop - start), at least 2.
    EXPECT_EQ(exposureRange(-3.0, 4.2).count, 8);
    EXPECT_EQ(exposureRange(1.0, 1.5).count, 2);
    EXPECT_THROW(exposureRange(2.0, 1.0), std::invalid_argument);
    EXPECT_THROW(exposureRange(0.0, INFINITY), std::invalid_argument);
}

TEST(HdrFlip, IdenticalImagesGiveZero) {
    const HdrPair p = glowOnBlack();
    const HdrFlipResult r = hdrFlip(p.reference, p.reference);
    EXPECT_EQ(r.mean, 0.0);
    EXPECT_EQ(r.errorMap.channelNames(), std::vector<std::string>{"hdrflip"});
}

TEST(HdrFlip, IsTheLargestLdrFlipOverTheExposures) {
    // With one exposure c (start = stop), HDR-ꟻLIP is LDR-ꟻLIP of the images exposed by 2^c and
    // tonemapped (ACES, clamped), taken as linear values.
    const HdrPair p = glowOnBlack();
    HdrFlipSettings one;
    one.range = ExposureRange{-1.0, -1.0, 0};
    const HdrFlipResult r = hdrFlip(p.reference, p.test, one);
    auto aces = [](const core::Image& hdr) {
        core::Image out = hdr;
        for (float& v : out.pixels()) {
            const float x = v * 0.5f;
            v = std::clamp((x * x * 0.9036f + x * 0.018f) / (x * x * 0.8748f + x * 0.354f + 0.14f),
                           0.0f, 1.0f);
        }
        return out;
    };
    FlipSettings linear;
    linear.input = FlipInput::Linear;
    const FlipResult ldr = flip(aces(p.reference), aces(p.test), linear);
    EXPECT_NEAR(r.mean, ldr.mean, 1e-6);
    // Over the reference's range every exposure's error is at most the HDR error.
    const HdrFlipResult all = hdrFlip(p.reference, p.test);
    EXPECT_GE(all.range.count, 5);
    for (int i = 0; i < all.range.count; ++i) {
        HdrFlipSettings at;
        const double c =
            all.range.start + i * (all.range.stop - all.range.start) / (all.range.count - 1);
        at.range = ExposureRange{c, c, 0};
        const HdrFlipResult single = hdrFlip(p.reference, p.test, at);
        for (std::size_t q = 0; q < single.errorMap.pixelCount(); ++q)
            // (1e-4: the exposure computed apart differs in its last bits)
            ASSERT_LE(single.errorMap.at(q, 0), all.errorMap.at(q, 0) + 1e-4f) << i << " " << q;
    }
}

TEST(HdrFlip, ABrighterSceneGivesTheSameError) {
    // The range follows the reference: exposing both images 8 times brighter shifts it by
    // 3 stops and leaves the error as it was.
    const HdrPair p = glowOnBlack();
    auto times8 = [](core::Image img) {
        for (float& v : img.pixels()) v *= 8.0f;
        return img;
    };
    const HdrFlipResult a = hdrFlip(p.reference, p.test);
    const HdrFlipResult b = hdrFlip(times8(p.reference), times8(p.test));
    EXPECT_NEAR(b.range.start, a.range.start - 3.0, 1e-5);
    EXPECT_NEAR(b.range.stop, a.range.stop - 3.0, 1e-5);
    EXPECT_NEAR(b.mean, a.mean, 1e-4);
}

// Reference: NVlabs' flip tool v1.6 (github.com/NVlabs/flip, commit 1eb247c, C++ tool built
// with g++ 12 -O2 -fopenmp) on the EXRs HdrReferencePairs.WriteForReferenceTools writes:
//   flip -r NAME.ref.exr -t NAME.test.exr [-cstart C -cstop C] -ppd 67 -v 1   (and -ppd 30)
// and FLIP::evaluate() of its FLIP.h for the error map (compare/testdata/reference_values.py
// --hdr prints both). On noisy_sky, which has no black pixel, the tool's own exposure range is
// ours (-7.5606 to 1.9568, 10 exposures; FLIP.h: -7.560559 to 1.956774). On glow_on_black it
// computes an infinite stop exposure (its median is black), no exposure and a mean of 0; there
// it is given our range. Tolerances as flip_test.cpp's: 1e-4 on the means, 2e-4 on pixels (the
// largest difference seen: 1.4e-6; the means agree to 1e-7).
TEST(HdrFlip, MatchesNvlabsReference) {
    const struct {
        HdrPair pair;
        double start, stop;
        int count;
        double mean67, mean30;
        std::vector<std::array<float, 3>> pixels;  // x, y, error at 67 ppd
    } expected[] = {
        // clang-format off
        {glowOnBlack(), -2.651069, 1.796123, 5, 0.111272, 0.100361,
         {{40, 35, 0.2333069f}, {21, 35, 0.4526153f}, {60, 35, 0.6851999f},
          {30, 20, 0.1144767f}, {5, 5, 0.0f}}},
        {noisySky(), -7.560559, 1.956774, 10, 0.047451, 0.090271,
         {{10, 10, 0.0109095f}, {50, 40, 0.0417343f}, {70, 20, 0.1563320f},
          {90, 60, 0.0597561f}}},
        // clang-format on
    };
    for (const auto& e : expected) {
        const HdrFlipResult r = hdrFlip(e.pair.reference, e.pair.test);
        EXPECT_NEAR(r.range.start, e.start, 1e-5) << e.pair.name;
        EXPECT_NEAR(r.range.stop, e.stop, 1e-5) << e.pair.name;
        EXPECT_EQ(r.range.count, e.count) << e.pair.name;
        EXPECT_NEAR(r.mean, e.mean67, 1e-4) << e.pair.name;
        for (const auto& [x, y, v] : e.pixels)
            EXPECT_NEAR(r.errorMap.at(static_cast<int>(x), static_cast<int>(y), 0), v, 2e-4)
                << e.pair.name << " " << x << "," << y;
        HdrFlipSettings at30;
        at30.ppd = 30.0;
        EXPECT_NEAR(hdrFlip(e.pair.reference, e.pair.test, at30).mean, e.mean30, 1e-4)
            << e.pair.name;
    }
}

// Writes the HDR pairs as EXRs into `dir` and reads them back: float32 EXRs hold every value
// exactly.
void writeHdrReferencePairs(const std::filesystem::path& dir) {
    std::filesystem::create_directories(dir);
    for (const HdrPair& p : {glowOnBlack(), noisySky()}) {
        core::writeImage(p.reference, dir / (p.name + ".ref.exr"));
        core::writeImage(p.test, dir / (p.name + ".test.exr"));
        for (const char* which : {".ref.exr", ".test.exr"}) {
            const core::Image& ours = which[1] == 'r' ? p.reference : p.test;
            const core::Image read = core::readImage(dir / (p.name + which));
            ASSERT_EQ(read.width(), ours.width());
            ASSERT_EQ(read.height(), ours.height());
            for (std::size_t i = 0; i < ours.pixelCount(); ++i)
                for (int c = 0; c < 3; ++c)
                    ASSERT_EQ(read.at(i, read.requireChannel(ours.channelNames()[c])),
                              ours.at(i, c))
                        << p.name << which << " pixel " << i;
        }
    }
}

// The writer of the test below, into the build tree's scratch folder, so that its round trip
// runs on every test run.
TEST(HdrReferencePairs, RoundTripThroughTheirExrs) {
    writeHdrReferencePairs(twinrender::testing::freshDir("hdr_reference_pairs"));
}

// Writes the HDR pairs as EXRs for NVlabs' flip tool when TWINRENDER_WRITE_TEST_PAIRS names a
// folder (compare/testdata/reference_values.py --hdr), with the exposure range we compute;
// skipped otherwise.
TEST(HdrReferencePairs, WriteForReferenceTools) {
    const char* dir = std::getenv("TWINRENDER_WRITE_TEST_PAIRS");
    if (!dir) GTEST_SKIP() << "set TWINRENDER_WRITE_TEST_PAIRS=DIR to write the test pairs";
    writeHdrReferencePairs(dir);
    for (const HdrPair& p : {glowOnBlack(), noisySky()}) {
        const HdrFlipResult r = hdrFlip(p.reference, p.test);
        std::printf("%s: start %.6f stop %.6f count %d mean %.6f\n", p.name.c_str(), r.range.start,
                    r.range.stop, r.range.count, r.mean);
    }
}

}  // namespace
}  // namespace twinrender::compare
