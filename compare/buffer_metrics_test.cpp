#include "compare/buffer_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/frame.h"

namespace twinrender::compare {
namespace {

// What a surface pixel holds; the defaults are a lit, front-facing pixel of body 0.
struct Surface {
    float z = 10.0f;
    float nx = 0.0f, ny = 0.0f, nz = 1.0f;
    float u = 0.5f, v = 0.5f;
    float id = 0.0f;
    float er = 0.0f, eg = 0.0f, eb = 0.0f;
    float shadow = 1.0f;
    float ao = 1.0f;
};

void cover(core::Image& img, int x, int y, const Surface& s = {}) {
    auto set = [&](const char* c, float value) { img.at(x, y, img.channelIndex(c)) = value; };
    set("A", 1.0f);
    set("Z", s.z);
    set("N.X", s.nx);
    set("N.Y", s.ny);
    set("N.Z", s.nz);
    set("uv.U", s.u);
    set("uv.V", s.v);
    set("id", s.id);
    set("emission.R", s.er);
    set("emission.G", s.eg);
    set("emission.B", s.eb);
    set("shadow", s.shadow);
    set("ao", s.ao);
}

// An AOV image whose pixels inside(x, y) are covered with surface(x, y).
template <typename Inside, typename SurfaceAt>
core::Image scene(int w, int h, Inside&& inside, SurfaceAt&& surface) {
    core::Image img = core::aov::makeImage(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (inside(x, y)) cover(img, x, y, surface(x, y));
    return img;
}

core::Image full(int w, int h) {
    return scene(
        w, h, [](int, int) { return true; }, [](int, int) { return Surface{}; });
}

bool isNaN(double v) {
    return std::isnan(v);
}

// ---- coverage.iou -------------------------------------------------------------------------

TEST(CoverageIou, RectangleShiftedHorizontally) {
    // A W x H rectangle and the same shifted right by k: intersection (W - k) H, union
    // (W + k) H, so IoU = (W - k) / (W + k) = 32 / 48 for W = 40, k = 8.
    auto rect = [](int x0) {
        return scene(
            80, 30, [x0](int x, int y) { return x >= x0 && x < x0 + 40 && y >= 5 && y < 25; },
            [](int, int) { return Surface{}; });
    };
    const Masks m = computeMasks(rect(10), rect(18));
    EXPECT_DOUBLE_EQ(coverageIou(m), 32.0 / 48.0);
}

TEST(CoverageIou, DiscShiftedByKPixels) {
    // Disc of radius R = 20 centred at (40.5, 32.5) (pixel centres at integers + 0.5 do not
    // land on the circle), and the same shifted by k = 6 pixels right. Exact value: the pixel
    // sets' counts, which the test counts independently; it also lies within 1 % of the
    // continuous lens area, I = 2 R^2 acos(k / 2R) - (k / 2) sqrt(4 R^2 - k^2),
    // IoU = I / (2 pi R^2 - I) = 1017.5 / 1495.8 = 0.680.
    const double R = 20.0, k = 6.0;
    auto inDisc = [R](double cx) {
        return [R, cx](int x, int y) {
            const double dx = x - cx, dy = y - 32.5;
            return dx * dx + dy * dy < R * R;
        };
    };
    const auto inRef = inDisc(40.5), inTest = inDisc(40.5 + k);
    const core::Image ref = scene(90, 65, inRef, [](int, int) { return Surface{}; });
    const core::Image test = scene(90, 65, inTest, [](int, int) { return Surface{}; });
    int both = 0, either = 0;
    for (int y = 0; y < 65; ++y)
        for (int x = 0; x < 90; ++x) {
            both += inRef(x, y) && inTest(x, y);
            either += inRef(x, y) || inTest(x, y);
        }
    const double iou = coverageIou(computeMasks(ref, test));
    EXPECT_DOUBLE_EQ(iou, static_cast<double>(both) / either);
    const double lens = 2 * R * R * std::acos(k / (2 * R)) - k / 2 * std::sqrt(4 * R * R - k * k);
    EXPECT_NEAR(iou, lens / (2 * std::numbers::pi * R * R - lens), 0.01);
}

TEST(CoverageIou, NothingCoveredInEitherAgrees) {
    const core::Image empty = core::aov::makeImage(10, 10);
    EXPECT_EQ(coverageIou(computeMasks(empty, empty)), 1.0);
    EXPECT_EQ(coverageIou(computeMasks(empty, full(10, 10))), 0.0);
}

// ---- silhouette.mean_px -------------------------------------------------------------------

TEST(Silhouette, FullHeightBandShiftedByKIsExactlyK) {
    // A band of columns 10..29 spanning the full image height, and the same shifted right by
    // k = 3. The image edge is no outline, so each outline is two full columns: reference 10
    // and 29, test 13 and 32. Every reference outline pixel is k from the test column on its
    // side (10 -> 13, 29 -> 32; the other column is 16 or 22 away) and vice versa, so the mean
    // over both outlines is exactly k.
    auto band = [](int x0) {
        return scene(
            60, 25, [x0](int x, int) { return x >= x0 && x < x0 + 20; },
            [](int, int) { return Surface{}; });
    };
    for (int k : {0, 1, 3, 7}) {
        const Masks m = computeMasks(band(10), band(10 + k));
        EXPECT_DOUBLE_EQ(silhouetteMeanPx(m), static_cast<double>(k)) << "k " << k;
    }
}

TEST(Silhouette, DiscShiftedEqualsTheDefinitionAndTheContinuousMean) {
    // Disc radius 25 shifted by k = 4 pixels right. Checked against the definition computed by
    // brute force (every pair of outline pixels), and loosely against the continuous value:
    // a point at angle t on one circle is k |cos t| (to first order in k / R) from the other,
    // whose mean over the circle is 2 k / pi = 2.546 pixels.
    const double R = 25.0;
    const int k = 4;
    auto disc = [R](double cx) {
        return scene(
            100, 70,
            [R, cx](int x, int y) {
                const double dx = x - cx, dy = y - 35.5;
                return dx * dx + dy * dy < R * R;
            },
            [](int, int) { return Surface{}; });
    };
    const Masks m = computeMasks(disc(45.5), disc(45.5 + k));
    const Mask a = outlineMask(m.referenceCovered), b = outlineMask(m.testCovered);
    auto nearest = [](const Mask& to, int x, int y) {
        double best = std::numeric_limits<double>::infinity();
        for (int qy = 0; qy < to.height(); ++qy)
            for (int qx = 0; qx < to.width(); ++qx)
                if (to(qx, qy)) best = std::min(best, std::hypot(x - qx, y - qy));
        return best;
    };
    double sum = 0.0;
    std::size_t n = 0;
    for (int y = 0; y < 70; ++y)
        for (int x = 0; x < 100; ++x) {
            if (a(x, y)) sum += nearest(b, x, y), ++n;
            if (b(x, y)) sum += nearest(a, x, y), ++n;
        }
    const double mean = silhouetteMeanPx(m);
    EXPECT_NEAR(mean, sum / static_cast<double>(n), 1e-9);
    EXPECT_NEAR(mean, 2.0 * k / std::numbers::pi, 0.35);
}

TEST(Silhouette, OutlineIsTheCoveredPixelsNextToUncoveredOnes) {
    // A 5x4 block at (2..6, 1..4) in a 10x6 image: its 14 rim pixels. A block touching the
    // image edge has no outline along that edge.
    Mask covered(10, 6);
    for (int y = 1; y <= 4; ++y)
        for (int x = 2; x <= 6; ++x) covered.set(x, y, true);
    EXPECT_EQ(outlineMask(covered).count(), 14u);
    EXPECT_FALSE(outlineMask(covered)(4, 2));
    Mask edge(10, 6);
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 4; ++x) edge.set(x, y, true);
    const Mask o = outlineMask(edge);
    EXPECT_EQ(o.count(), 6u);  // column 3 only
    for (int y = 0; y < 6; ++y) EXPECT_TRUE(o(3, y));
}

TEST(Silhouette, NoOutlinesIsNaNAndOneMissingIsInfinite) {
    const core::Image empty = core::aov::makeImage(20, 20);
    EXPECT_TRUE(isNaN(silhouetteMeanPx(computeMasks(empty, empty))));
    EXPECT_TRUE(isNaN(silhouetteMeanPx(computeMasks(full(20, 20), full(20, 20)))));
    const core::Image block = scene(
        20, 20, [](int x, int y) { return x > 5 && x < 12 && y > 5 && y < 12; },
        [](int, int) { return Surface{}; });
    EXPECT_EQ(silhouetteMeanPx(computeMasks(block, empty)),
              std::numeric_limits<double>::infinity());
    EXPECT_EQ(silhouetteMeanPx(computeMasks(block, block)), 0.0);
}

// ---- depth.rel_mean -----------------------------------------------------------------------

TEST(Depth, KnownRelativeOffset) {
    // Test depth 4 % farther everywhere: |1.04 Z - Z| / Z = 0.04 at every covered pixel. The
    // depths vary over the image; float storage of 1.04 Z costs at most 2^-24 relative.
    auto depthAt = [](int x, int y) { return 2.0f + 0.37f * x + 0.11f * y; };
    const core::Image ref = scene(
        30, 20, [](int x, int) { return x < 25; },
        [&](int x, int y) {
            Surface s;
            s.z = depthAt(x, y);
            return s;
        });
    const core::Image test = scene(
        30, 20, [](int x, int) { return x >= 5; },
        [&](int x, int y) {
            Surface s;
            s.z = static_cast<float>(1.04 * depthAt(x, y));
            return s;
        });
    const DepthResult r = depthError(ref, test, computeMasks(ref, test));
    EXPECT_NEAR(r.relMean, 0.04, 1e-6);
    ASSERT_EQ(r.errorMap.channelNames(), std::vector<std::string>{"relative_error"});
    EXPECT_NEAR(r.errorMap.at(10, 10, 0), 0.04f, 1e-6f);
    EXPECT_EQ(r.errorMap.at(2, 10, 0), 0.0f);  // covered in the reference only: outside the mask
}

TEST(Depth, NothingCoveredInBothIsNaN) {
    const core::Image empty = core::aov::makeImage(8, 8);
    EXPECT_TRUE(isNaN(depthError(empty, full(8, 8), computeMasks(empty, full(8, 8))).relMean));
}

// ---- id.mismatch --------------------------------------------------------------------------

TEST(Id, SwappedBodiesInAKnownFraction) {
    // 40x30, all covered, bodies 1 (left half) and 2 (right half). The test swaps the two ids
    // in columns 14..25 (12 of 40 columns: 0.3 of the pixels), and leaves rows 0..4 uncovered:
    // those 200 pixels are not covered in both and do not count, so the fraction stays
    // 12 * 25 / (40 * 25) = 0.3.
    auto idAt = [](int x) { return x < 20 ? 1.0f : 2.0f; };
    const core::Image ref = scene(
        40, 30, [](int, int) { return true; },
        [&](int x, int) {
            Surface s;
            s.id = idAt(x);
            return s;
        });
    const core::Image test = scene(
        40, 30, [](int, int y) { return y >= 5; },
        [&](int x, int) {
            Surface s;
            s.id = (x >= 14 && x <= 25) ? 3.0f - idAt(x) : idAt(x);
            return s;
        });
    const IdResult r = idMismatch(ref, test, computeMasks(ref, test));
    EXPECT_DOUBLE_EQ(r.mismatch, 0.3);
    EXPECT_EQ(r.errorMap.at(15, 10, 0), 1.0f);
    EXPECT_EQ(r.errorMap.at(10, 10, 0), 0.0f);
    EXPECT_EQ(r.errorMap.at(15, 2, 0), 0.0f);
}

// ---- normal.mean_deg, normal.p95_deg ------------------------------------------------------

TEST(Normal, AngleOfKnownVectors) {
    EXPECT_NEAR(angleDeg(1, 0, 0, 0, 1, 0), 90.0, 1e-12);
    EXPECT_NEAR(angleDeg(1, 0, 0, -1, 0, 0), 180.0, 1e-12);
    EXPECT_NEAR(angleDeg(0, 0, 2, 0, 0, 0.5), 0.0, 1e-12);  // lengths do not matter
    EXPECT_NEAR(angleDeg(1, 0, 0, 1, 1, 0), 45.0, 1e-12);
    // Nearly parallel: 1e-7 rad, where acos of the dot product would give 0.
    EXPECT_NEAR(angleDeg(1, 0, 0, 1, 1e-7, 0), 1e-7 * 180.0 / std::numbers::pi, 1e-17);
    EXPECT_EQ(angleDeg(0, 0, 0, 1, 0, 0), 90.0);  // no direction
}

TEST(Normal, QuantileIsLinearBetweenOrderStatistics) {
    // numpy.percentile([5, 1, 4, 2, 3], 95) = 4.8: position 0.95 * 4 = 3.8 between 4 and 5.
    std::vector<double> v = {5, 1, 4, 2, 3};
    EXPECT_DOUBLE_EQ(quantile(v, 0.95), 4.8);
    v = {5, 1, 4, 2, 3};
    EXPECT_DOUBLE_EQ(quantile(v, 0.5), 3.0);
    v = {7};
    EXPECT_DOUBLE_EQ(quantile(v, 0.95), 7.0);
    v.clear();
    EXPECT_TRUE(isNaN(quantile(v, 0.95)));
}

TEST(Normal, FieldRotatedByAKnownAngle) {
    // Reference normals in the x-z plane, turning with x: n = (sin p, 0, cos p). The test turns
    // each by 30 degrees about the y axis, which is perpendicular to every one of them, so
    // every angle is exactly 30 degrees: mean = p95 = 30 (up to float storage, ~1e-5 deg).
    const double t = 30.0 * std::numbers::pi / 180.0;
    auto field = [](double extra) {
        return [extra](int x, int) {
            const double p = -0.8 + 0.03 * x + extra;
            Surface s;
            s.nx = static_cast<float>(std::sin(p));
            s.ny = 0.0f;
            s.nz = static_cast<float>(std::cos(p));
            return s;
        };
    };
    auto disc = [](int x, int y) { return (x - 30) * (x - 30) + (y - 25) * (y - 25) < 400; };
    const core::Image ref = scene(60, 50, disc, field(0.0));
    const core::Image test = scene(60, 50, disc, field(t));
    const NormalResult r = normalError(ref, test, computeMasks(ref, test));
    EXPECT_NEAR(r.meanDeg, 30.0, 1e-4);
    EXPECT_NEAR(r.p95Deg, 30.0, 1e-4);
    ASSERT_EQ(r.errorMap.channelNames(), std::vector<std::string>{"angle_deg"});
    EXPECT_NEAR(r.errorMap.at(30, 25, 0), 30.0f, 1e-4f);
    EXPECT_EQ(r.errorMap.at(0, 0, 0), 0.0f);  // background
}

TEST(Normal, PooledOverInteriorPixelsOnly) {
    // Reference and test agree everywhere but on the outermost ring of a block, which is not
    // interior (radius 2): mean and p95 stay 0 while the map shows the ring.
    auto block = [](int x, int y) { return x >= 5 && x < 25 && y >= 5 && y < 25; };
    const core::Image ref = scene(30, 30, block, [](int, int) { return Surface{}; });
    const core::Image test = scene(30, 30, block, [](int x, int y) {
        Surface s;
        if (x == 5 || x == 24 || y == 5 || y == 24) s.nx = 1.0f, s.nz = 0.0f;
        return s;
    });
    const NormalResult r = normalError(ref, test, computeMasks(ref, test));
    EXPECT_EQ(r.meanDeg, 0.0);
    EXPECT_EQ(r.p95Deg, 0.0);
    EXPECT_NEAR(r.errorMap.at(5, 10, 0), 90.0f, 1e-5f);
}

TEST(Normal, P95SeparatesATail) {
    // 10 % of the interior pixels (every tenth column) off by 60 degrees, the rest exact: the
    // mean is 6 degrees and the 95th percentile 60.
    const core::Image ref = full(50, 20);
    const core::Image test = scene(
        50, 20, [](int, int) { return true; },
        [](int x, int) {
            Surface s;
            if (x % 10 == 4) {
                s.nx = static_cast<float>(std::sin(std::numbers::pi / 3));
                s.nz = static_cast<float>(std::cos(std::numbers::pi / 3));
            }
            return s;
        });
    const NormalResult r = normalError(ref, test, computeMasks(ref, test));
    EXPECT_NEAR(r.meanDeg, 6.0, 1e-4);
    EXPECT_NEAR(r.p95Deg, 60.0, 1e-4);
}

// ---- uv.mean ------------------------------------------------------------------------------

TEST(Uv, SeamAwareDistance) {
    EXPECT_NEAR(uvDistance(0.99, 0.5, 0.01, 0.5), 0.02, 1e-12);
    EXPECT_NEAR(uvDistance(0.01, 0.5, 0.99, 0.5), 0.02, 1e-12);
    EXPECT_NEAR(uvDistance(0.2, 0.1, 0.23, 0.14), 0.05, 1e-12);  // 3-4-5
    EXPECT_NEAR(uvDistance(0.5, 0.0, 0.0, 0.0), 0.5, 1e-12);     // farthest round the seam
    EXPECT_NEAR(uvDistance(0.98, 0.3, 1.01, 0.3), 0.03, 1e-12);  // written just past 1
}

TEST(Uv, AcrossTheSeamIsTwoHundredths) {
    // Reference u = 0.99, test u = 0.01, same v: 0.02 everywhere, not 0.98.
    const core::Image ref = scene(
        20, 20, [](int, int) { return true; },
        [](int, int) {
            Surface s;
            s.u = 0.99f;
            return s;
        });
    const core::Image test = scene(
        20, 20, [](int, int) { return true; },
        [](int, int) {
            Surface s;
            s.u = 0.01f;
            return s;
        });
    const UvResult r = uvError(ref, test, computeMasks(ref, test));
    EXPECT_NEAR(r.mean, 0.02, 1e-6);  // 0.99f and 0.01f differ from 0.99 and 0.01 by < 3e-8
    ASSERT_EQ(r.errorMap.channelNames(), std::vector<std::string>{"uv_error"});
    EXPECT_NEAR(r.errorMap.at(3, 3, 0), 0.02f, 1e-6f);
}

// ---- emission.rmse ------------------------------------------------------------------------

TEST(Emission, ConstantDifference) {
    // Differences (0.375, 0, 0.5) at every pixel covered in both: mean square over the three
    // channels (0.140625 + 0.25) / 3, RMSE its root. Exact in float.
    const core::Image ref = scene(
        16, 12, [](int, int) { return true; },
        [](int, int) {
            Surface s;
            s.er = 1.0f;
            s.eg = 2.0f;
            return s;
        });
    const core::Image test = scene(
        16, 12, [](int, int) { return true; },
        [](int, int) {
            Surface s;
            s.er = 1.375f;
            s.eg = 2.0f;
            s.eb = 0.5f;
            return s;
        });
    const EmissionResult r = emissionError(ref, test, computeMasks(ref, test));
    const double expected = std::sqrt((0.140625 + 0.25) / 3.0);
    EXPECT_DOUBLE_EQ(r.rmse, expected);
    EXPECT_FLOAT_EQ(r.errorMap.at(4, 4, 0), static_cast<float>(expected));
}

// ---- flux.ratio ---------------------------------------------------------------------------

TEST(FluxRatio, SumOfTheBeautyOverTheReferences) {
    // The reference: one pixel of (3, 2, 1), sum 6. The test spreads less light over four
    // pixels of (0.5, 0.25, 0) each, sum 3: ratio 0.5, wherever the pixels lie.
    core::Image ref = core::aov::makeImage(8, 6);
    core::Image test = core::aov::makeImage(8, 6);
    auto set = [](core::Image& img, int x, int y, float r, float g, float b) {
        img.at(x, y, img.channelIndex("R")) = r;
        img.at(x, y, img.channelIndex("G")) = g;
        img.at(x, y, img.channelIndex("B")) = b;
    };
    set(ref, 3, 2, 3.0f, 2.0f, 1.0f);
    for (int y = 4; y < 6; ++y)
        for (int x = 0; x < 2; ++x) set(test, x, y, 0.5f, 0.25f, 0.0f);
    EXPECT_DOUBLE_EQ(fluxRatio(ref, test), 0.5);
    EXPECT_DOUBLE_EQ(fluxRatio(ref, ref), 1.0);
    EXPECT_DOUBLE_EQ(fluxRatio(test, core::aov::makeImage(8, 6)), 0.0);  // all light lost
    EXPECT_TRUE(isNaN(fluxRatio(core::aov::makeImage(8, 6), test)));     // nothing to keep
}

// ---- smoothness.ratio ---------------------------------------------------------------------

// A field turning by `step` radians per column about the y axis: every horizontal neighbour
// pair is `step` apart, every vertical pair 0, so a pixel's mean over its four neighbours is
// (step + step + 0 + 0) / 4 = step / 2, and so is the roughness.
core::Image turningField(int w, int h, double step) {
    return scene(
        w, h, [](int, int) { return true; },
        [step](int x, int) {
            Surface s;
            s.nx = static_cast<float>(std::sin(step * x));
            s.nz = static_cast<float>(std::cos(step * x));
            return s;
        });
}

TEST(Smoothness, KnownRoughnessAndRatio) {
    const double step = 0.01;  // radians per column, 0.573 degrees
    const core::Image ref = turningField(40, 30, step);
    const core::Image test = turningField(40, 30, 2 * step);
    const SmoothnessResult r = smoothness(ref, test, computeMasks(ref, test));
    const double stepDeg = step * 180.0 / std::numbers::pi;
    EXPECT_NEAR(r.referenceRoughnessDeg, stepDeg / 2, 1e-5);
    EXPECT_NEAR(r.testRoughnessDeg, stepDeg, 1e-5);
    EXPECT_NEAR(r.ratio, 2.0, 1e-4);
    // The image edge is not eroded; a pixel needs four neighbours in the image: 38 x 28.
    EXPECT_EQ(r.pixels, 38u * 28u);
}

TEST(Smoothness, IdenticalFieldIsOneAndANoisierOneIsAbove) {
    const core::Image ref = turningField(40, 30, 0.02);
    core::Image noisy = ref;
    std::uint32_t state = 77u;
    auto next = [&] {
        state = 1664525u * state + 1013904223u;
        return static_cast<float>(state >> 8) / 16777216.0f - 0.5f;
    };
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x)
            for (const char* c : {"N.X", "N.Y", "N.Z"})
                noisy.at(x, y, noisy.channelIndex(c)) += 0.1f * next();
    EXPECT_EQ(smoothness(ref, ref, computeMasks(ref, ref)).ratio, 1.0);
    EXPECT_GT(smoothness(ref, noisy, computeMasks(ref, noisy)).ratio, 1.5);
    // And the other way round: a test smoother than the reference is below 1.
    EXPECT_LT(smoothness(noisy, ref, computeMasks(noisy, ref)).ratio, 1.0 / 1.5);
}

TEST(Smoothness, FlatFieldsAndEmptyMask) {
    const core::Image flat = full(20, 20);
    EXPECT_EQ(smoothness(flat, flat, computeMasks(flat, flat)).ratio, 1.0);
    EXPECT_EQ(smoothness(flat, turningField(20, 20, 0.1), computeMasks(flat, flat)).ratio,
              std::numeric_limits<double>::infinity());
    const core::Image empty = core::aov::makeImage(20, 20);
    const SmoothnessResult r = smoothness(empty, empty, computeMasks(empty, empty));
    EXPECT_TRUE(isNaN(r.ratio));
    EXPECT_EQ(r.pixels, 0u);
}

// ---- shadow -------------------------------------------------------------------------------

TEST(Shadow, KnownShadowMasks) {
    // 20 columns x 10 rows, all covered, light unknown (every pixel counts). Reference shadow
    // in columns 0..7, test shadow in columns 4..11: shadowed in both 4..7 (4 columns), in
    // either 0..11 (12): IoU 4 / 12. False shadow (test only) columns 8..11: 4 / 20 = 0.2;
    // missed (reference only) columns 0..3: 0.2.
    auto shadowed = [](int lo, int hi) {
        return scene(
            20, 10, [](int, int) { return true; },
            [lo, hi](int x, int) {
                Surface s;
                s.shadow = (x >= lo && x <= hi) ? 0.0f : 1.0f;
                return s;
            });
    };
    const core::Image ref = shadowed(0, 7), test = shadowed(4, 11);
    const ShadowResult r = shadowError(ref, test, computeMasks(ref, test));
    EXPECT_DOUBLE_EQ(r.iou, 4.0 / 12.0);
    EXPECT_DOUBLE_EQ(r.falseShadow, 0.2);
    EXPECT_DOUBLE_EQ(r.missedShadow, 0.2);
    ASSERT_EQ(r.errorMap.channelNames(), std::vector<std::string>{"disagreement"});
    EXPECT_EQ(r.errorMap.at(9, 3, 0), SHADOW_FALSE);
    EXPECT_EQ(r.errorMap.at(1, 3, 0), SHADOW_MISSED);
    EXPECT_EQ(r.errorMap.at(5, 3, 0), 0.0f);
    EXPECT_EQ(r.errorMap.at(15, 3, 0), 0.0f);
}

TEST(Shadow, KnownVisibilityErrorAndLeak) {
    // 10 columns x 4 rows, all covered, light unknown. Reference visibility by column:
    // 0 0 0 0 0.5 0.5 1 1 1 1; test: 0.2 0.6 1 0 0.5 0 1 1 0.9 0.4.
    // Absolute errors: 0.2 0.6 1 0 0 0.5 0 0 0.1 0.6, sum 3.0 over 10 columns: mae 0.3.
    // Leak: full shadow in the reference (columns 0..3) and test above 0.5 (columns 1, 2):
    // 2 of 10 columns, 0.2. Column 4's 0.5 is not a leak (not full shadow).
    const float ref[10] = {0.0f, 0.0f, 0.0f, 0.0f, 0.5f, 0.5f, 1.0f, 1.0f, 1.0f, 1.0f};
    const float tst[10] = {0.2f, 0.6f, 1.0f, 0.0f, 0.5f, 0.0f, 1.0f, 1.0f, 0.9f, 0.4f};
    auto img = [](const float* v) {
        return scene(
            10, 4, [](int, int) { return true; },
            [v](int x, int) {
                Surface s;
                s.shadow = v[x];
                return s;
            });
    };
    const core::Image reference = img(ref), test = img(tst);
    const ShadowResult r = shadowError(reference, test, computeMasks(reference, test));
    EXPECT_NEAR(r.mae, 0.3, 1e-7);
    EXPECT_DOUBLE_EQ(r.leak, 0.2);
    // Against itself: no error, no leak.
    const ShadowResult same = shadowError(reference, reference, computeMasks(reference, reference));
    EXPECT_EQ(same.mae, 0.0);
    EXPECT_EQ(same.leak, 0.0);
}

TEST(Shadow, OnlySurfacesFacingTheLightCount) {
    // Rows 0..4 face the light (N.Z = 1, light travelling along -z), rows 5..9 face away: their
    // shadow (self-shadowing, N.L <= 0) is not a shadow-map question and is ignored. Reference
    // lit everywhere; the test shadows columns 0..4 of every row: 5 of the 20 columns in the
    // counted rows are false shadow.
    auto img = [](bool shadowLeft) {
        return scene(
            20, 10, [](int, int) { return true; },
            [shadowLeft](int x, int y) {
                Surface s;
                s.nz = y < 5 ? 1.0f : -1.0f;
                s.shadow = (shadowLeft && x < 5) ? 0.0f : 1.0f;
                return s;
            });
    };
    const core::Image ref = img(false), test = img(true);
    MaskSettings s;
    s.hasLight = true;
    s.lightDirection = {0.0, 0.0, -1.0};
    const ShadowResult r = shadowError(ref, test, computeMasks(ref, test, s));
    EXPECT_DOUBLE_EQ(r.falseShadow, 0.25);
    EXPECT_DOUBLE_EQ(r.missedShadow, 0.0);
    EXPECT_DOUBLE_EQ(r.iou, 0.0);
    EXPECT_EQ(r.errorMap.at(2, 7, 0), 0.0f);  // facing away: outside the mask
    EXPECT_EQ(r.errorMap.at(2, 2, 0), SHADOW_FALSE);
}

TEST(Shadow, NoShadowInEitherAgreesAndAnEmptyMaskIsNaN) {
    const core::Image lit = full(10, 10);
    const ShadowResult agree = shadowError(lit, lit, computeMasks(lit, lit));
    EXPECT_EQ(agree.iou, 1.0);
    EXPECT_EQ(agree.falseShadow, 0.0);
    EXPECT_EQ(agree.missedShadow, 0.0);
    EXPECT_EQ(agree.mae, 0.0);
    EXPECT_EQ(agree.leak, 0.0);
    const core::Image empty = core::aov::makeImage(10, 10);
    const ShadowResult none = shadowError(empty, lit, computeMasks(empty, lit));
    EXPECT_TRUE(isNaN(none.iou) && isNaN(none.falseShadow) && isNaN(none.missedShadow));
    EXPECT_TRUE(isNaN(none.mae) && isNaN(none.leak));
}

// ---- every metric -------------------------------------------------------------------------

// ---- ao ------------------------------------------------------------------------------------

TEST(AmbientOcclusion, KnownErrorsBiasAndHalo) {
    // 20 columns x 10 rows, all covered; columns 0..9 at depth 10, 10..19 at depth 20: a depth
    // edge (a jump of 100 %) on columns 9 and 10. Reference open fraction 0.5 everywhere; test
    // 0.7 on columns 0..4 (+0.2: too light), 0.2 on columns 8..11 (-0.3: a dark halo), 0.5
    // elsewhere. Per row: |error| sum 5 x 0.2 + 4 x 0.3 = 2.2, error sum 1.0 - 1.2 = -0.2, over
    // 20 columns: mean_abs 0.11, bias -0.01. The halo band (within 4 px of columns 9 or 10) is
    // columns 5..14: |error| 1.2 over 10 columns, 0.12.
    auto img = [](bool test) {
        return scene(
            20, 10, [](int, int) { return true; },
            [test](int x, int) {
                Surface s;
                s.z = x < 10 ? 10.0f : 20.0f;
                s.ao = 0.5f;
                if (test && x <= 4) s.ao = 0.7f;
                if (test && x >= 8 && x <= 11) s.ao = 0.2f;
                return s;
            });
    };
    const core::Image reference = img(false), test = img(true);
    const Masks masks = computeMasks(reference, test);
    const Mask edges = depthEdgeMask(reference, masks.referenceCovered);
    EXPECT_EQ(edges.count(), 20u);
    EXPECT_TRUE(edges(9, 4) && edges(10, 4) && !edges(8, 4) && !edges(0, 0));
    const AoResult r = aoError(reference, test, masks);
    EXPECT_NEAR(r.meanAbs, 0.11, 1e-6);
    EXPECT_NEAR(r.bias, -0.01, 1e-6);
    EXPECT_NEAR(r.halo, 0.12, 1e-6);
    ASSERT_EQ(r.errorMap.channelNames(), std::vector<std::string>{"abs_error"});
    EXPECT_NEAR(r.errorMap.at(2, 3, 0), 0.2, 1e-6);
    EXPECT_NEAR(r.errorMap.at(9, 3, 0), 0.3, 1e-6);
}

TEST(AmbientOcclusion, GrainIsFineNoiseAndBandingIsCoarse) {
    // 40 x 40 pixels, all covered and interior; the reference open everywhere at 0.5.
    auto img = [](auto errorAt) {
        return scene(
            40, 40, [](int, int) { return true; },
            [errorAt](int x, int y) {
                Surface s;
                s.ao = 0.5f + errorAt(x, y);
                return s;
            });
    };
    const core::Image reference = img([](int, int) { return 0.0f; });
    auto noise = [&](auto errorAt) {
        const core::Image test = img(errorAt);
        return aoError(reference, test, computeMasks(reference, test));
    };
    // A constant error is bias alone: no grain, no banding.
    const AoResult constant = noise([](int, int) { return 0.1f; });
    EXPECT_NEAR(constant.bias, 0.1, 1e-6);
    EXPECT_NEAR(constant.grain, 0.0, 1e-6);
    EXPECT_NEAR(constant.banding, 0.0, 1e-6);
    // A checkerboard of +-0.1: pixel-fine noise. A 9 x 9 window holds 41 of one sign and 40 of
    // the other (its mean +-0.1 / 81), so grain is 0.1 (1 - 1/81) = 0.0988 away from the image
    // edge, where windows are cut; banding is about 0.1 / 81.
    const AoResult checker = noise([](int x, int y) { return (x + y) % 2 ? 0.1f : -0.1f; });
    EXPECT_GT(checker.grain, 0.095);
    EXPECT_LT(checker.grain, 0.1);
    EXPECT_LT(checker.banding, 0.01);
    // Two bands, +0.1 on the left half and -0.1 on the right: coarse. The local mean follows
    // the bands but within 4 px of their border: banding near 0.1, grain only at the border.
    const AoResult bands = noise([](int x, int) { return x < 20 ? 0.1f : -0.1f; });
    EXPECT_GT(bands.banding, 0.08);
    EXPECT_LT(bands.grain, 0.05);
}

TEST(AmbientOcclusion, FalseOcclusionWhereOpenAndMissedShareWhereOccluded) {
    // 10 x 10 pixels, all covered, by column. The reference is open (1) on columns 0..3,
    // 0.95 on 4..5 (neither open nor occluded: in no sum) and 0.5 on 6..9. The test adds 0.1,
    // 0.1, 0 and 0.2 of occlusion on the open columns: ao.false = 0.4 / 4 = 0.1. On the
    // occluded ones (occlusion 0.5 each, 2 a row) it finds all (0.5), half (0.75), none (1)
    // and more than all (0.3, which misses nothing): ao.missed = (0 + 0.25 + 0.5 + 0) / 2.
    const float reference[10] = {1, 1, 1, 1, 0.95f, 0.95f, 0.5f, 0.5f, 0.5f, 0.5f};
    const float test[10] = {0.9f, 0.9f, 1, 0.8f, 0.5f, 0.5f, 0.5f, 0.75f, 1, 0.3f};
    auto img = [](const float* ao) {
        return scene(
            10, 10, [](int, int) { return true; },
            [ao](int x, int) {
                Surface s;
                s.ao = ao[x];
                return s;
            });
    };
    const core::Image ref = img(reference), tst = img(test);
    const AoResult r = aoError(ref, tst, computeMasks(ref, tst));
    EXPECT_NEAR(r.falseOcclusion, 0.1, 1e-6);
    EXPECT_NEAR(r.missed, 0.375, 1e-6);
    // No occlusion at all misses every bit of it and adds none.
    const float open[10] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
    const core::Image none = img(open);
    const AoResult n = aoError(ref, none, computeMasks(ref, none));
    EXPECT_EQ(n.falseOcclusion, 0.0);
    EXPECT_NEAR(n.missed, 1.0, 1e-6);
}

TEST(AmbientOcclusion, NoEdgeNoHaloAndAnEmptyMaskIsNaN) {
    const core::Image flat = full(12, 8);
    const AoResult same = aoError(flat, flat, computeMasks(flat, flat));
    EXPECT_EQ(same.meanAbs, 0.0);
    EXPECT_EQ(same.bias, 0.0);
    EXPECT_TRUE(isNaN(same.halo));  // no depth edge: no band
    EXPECT_EQ(same.falseOcclusion, 0.0);
    EXPECT_TRUE(isNaN(same.missed));  // open everywhere: no occlusion to miss
    const core::Image empty = core::aov::makeImage(12, 8);
    const AoResult none = aoError(empty, empty, computeMasks(empty, empty));
    EXPECT_TRUE(isNaN(none.meanAbs) && isNaN(none.bias) && isNaN(none.halo));
    EXPECT_TRUE(isNaN(none.grain) && isNaN(none.banding));
    EXPECT_TRUE(isNaN(none.falseOcclusion) && isNaN(none.missed));
}

TEST(BufferMetrics, EmptyMasksGiveNaN) {
    const core::Image empty = core::aov::makeImage(12, 12);
    const core::Image other = full(12, 12);
    const Masks m = computeMasks(empty, other);
    EXPECT_TRUE(isNaN(depthError(empty, other, m).relMean));
    EXPECT_TRUE(isNaN(idMismatch(empty, other, m).mismatch));
    EXPECT_TRUE(isNaN(normalError(empty, other, m).meanDeg));
    EXPECT_TRUE(isNaN(normalError(empty, other, m).p95Deg));
    EXPECT_TRUE(isNaN(uvError(empty, other, m).mean));
    EXPECT_TRUE(isNaN(emissionError(empty, other, m).rmse));
    EXPECT_TRUE(isNaN(smoothness(empty, other, m).ratio));
    EXPECT_TRUE(isNaN(shadowError(empty, other, m).iou));
}

TEST(BufferMetrics, MissingChannelIsNotComparableAndNamed) {
    const core::Image ref = full(8, 8);
    const Masks m = computeMasks(ref, ref);
    std::vector<std::string> names = core::aov::channelNames();
    std::erase(names, std::string("uv.V"));
    const core::Image noV = ref.select(names);
    try {
        uvError(ref, noV, m);
        FAIL() << "expected NotComparableError";
    } catch (const core::NotComparableError& e) {
        EXPECT_NE(std::string(e.what()).find("uv.V"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("test"), std::string::npos) << e.what();
    }
}

TEST(BufferMetrics, DifferentSizesAreNotComparable) {
    const core::Image a = full(8, 8), b = full(9, 8);
    EXPECT_THROW(depthError(a, b, computeMasks(a, a)), core::NotComparableError);
}

TEST(IndirectLight, MissedAndFalseLightAgainstTheReferencesLitPixels) {
    // 10 x 10 covered pixels. The reference lights the five left columns with E = (1, 1, 1)
    // (luminance 1, its 99th percentile, so lit means >= 0.05). The test lights three of them
    // alike, leaves two dark (missed: 2 of 5 lit columns) and lights the two right columns
    // with luminance 0.5 where the reference is dark (false: 2 of 5 dark columns).
    core::Image reference = full(10, 10), test = full(10, 10);
    const int c = reference.channelIndex("irradiance.R");
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 10; ++x)
            for (int k = 0; k < 3; ++k) {
                reference.at(x, y, c + k) = x < 5 ? 1.0f : 0.0f;
                test.at(x, y, c + k) = x < 3 ? 1.0f : x >= 8 ? 0.5f : 0.0f;
            }
    ASSERT_TRUE(hasIrradiance(reference, test));
    const IndirectResult r = indirectError(reference, test, computeMasks(reference, test));
    EXPECT_NEAR(r.threshold, 0.05, 1e-6);
    EXPECT_NEAR(r.missed, 0.4, 1e-9);
    EXPECT_NEAR(r.falseLight, 0.4, 1e-9);
    // 20 pixels off by 1, 20 by 0.5: sqrt((20 + 5) / 100).
    EXPECT_NEAR(r.rmse, 0.5, 1e-6);
    EXPECT_NEAR(r.errorMap.at(3, 0, 0), 1.0, 1e-6);
    EXPECT_NEAR(r.errorMap.at(9, 0, 0), 0.5, 1e-6);
    // A scene without such light has none: the metrics are left out.
    const core::Image dark = full(10, 10);
    EXPECT_FALSE(hasIrradiance(dark, dark));
}

TEST(Inscatter, ErrorOverThePixelsWhereEitherFrameHasAny) {
    // 10 x 10 pixels, covered or not. The reference's atmosphere covers the four left columns
    // with in-scatter (0.2, 0.2, 0.2) (luminance 0.2); the test's the same, but 0.3 in column 0
    // and it also lights column 4 with 0.1; the five right columns have none in either and are
    // left out: 50 pixels, 10 off by 0.1 and 10 by 0.1.
    core::Image reference = full(10, 10), test = full(10, 10);
    const int c = reference.channelIndex("inscatter.R");
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 10; ++x)
            for (int k = 0; k < 3; ++k) {
                reference.at(x, y, c + k) = x < 4 ? 0.2f : 0.0f;
                test.at(x, y, c + k) = x == 0 ? 0.3f : x < 4 ? 0.2f : x == 4 ? 0.1f : 0.0f;
            }
    ASSERT_TRUE(hasInscatter(reference, test));
    const InscatterResult r = inscatterError(reference, test);
    // sqrt(20 x 0.01 / 50); over the reference's sqrt(40 x 0.04 / 50).
    EXPECT_NEAR(r.rmse, std::sqrt(0.2 / 50.0), 1e-6);
    EXPECT_NEAR(r.rel, std::sqrt(0.2 / 1.6), 1e-5);
    EXPECT_NEAR(r.errorMap.at(0, 3, 0), 0.1, 1e-6);
    EXPECT_NEAR(r.errorMap.at(2, 3, 0), 0.0, 1e-6);
    // Without an atmosphere, no in-scatter: the metrics are left out.
    const core::Image clear = full(10, 10);
    EXPECT_FALSE(hasInscatter(clear, clear));
}

}  // namespace
}  // namespace twinrender::compare
