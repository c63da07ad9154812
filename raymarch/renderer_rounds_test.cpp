// The reference's secondary estimates in rounds (raymarch.ao_error, emissive_error, sun_error;
// raymarch/progressive_strata.h) against the closed forms of raymarch/renderer_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <string>

#include "raymarch/ao_hemisphere.h"
#include "raymarch/testing/renderer_scenes.h"

namespace tr = twinrender;
using tr::core::Image;
using tr::raymarch::testing::render;
using tr::raymarch::testing::SphereOverFloor;

namespace {

// A hit sample whose 16 first directions agree states an error of 0 and stops there: a
// feature that none of them met is invisible to its rounds. For a pixel whose true share of
// the other outcome is q that happens with probability at most (1 - q)^16: in each of the 16
// strata the direction misses the share q_c of it with probability 1 - 16 q_c, and the
// product of those, at a given sum of the q_c, is largest when they are equal.
double allAlikeBound(double q) {
    return std::pow(1.0 - q, 16.0);
}

// What a closed-form test of rounds checks at its end: no pixel `outside` its error, no more
// pixels whose first 16 directions agreed (`alike`) than `alikeBound` (the sum of
// allAlikeBound over the pixels) lets through, the count of independent rare events within 4
// of its spread, and every estimate of the frame below the target (none reached the cap).
void expectWithinTheTarget(int outside, int alike, double alikeBound, const tr::core::Frame& frame,
                           const std::string& kind, double target) {
    EXPECT_EQ(outside, 0);
    EXPECT_LE(alike, alikeBound + 4.0 * std::sqrt(alikeBound) + 1.0) << alikeBound;
    EXPECT_EQ(frame.counters.at(kind + "_at_cap"), 0.0);
    EXPECT_LT(frame.counters.at(kind + "_standard_error_max"), target);
}

}  // namespace

TEST(RaymarchRounds, AmbientOcclusionMatchesTheClosedFormWithinItsTarget) {
    // The floor under the sphere (Raymarch.AmbientOcclusionOfAFloorByASphereMatchesTheClosedForm)
    // with raymarch.ao_error = 0.03 and 64 samples: each hit takes 16, 64 or 256 directions.
    // A pixel that stopped below the cap states an error below the target, one at the cap at
    // most the binomial bound of 256 directions: within 4 of the larger. Every floor point
    // here sees the sphere, in the share (r / d)^2 cos(beta) of its hemisphere, so a pixel
    // that holds exactly 1 is one whose 16 first directions all missed it: as many as
    // allAlikeBound lets through. (Those early stops bias the mean, so it is not checked.)
    SphereOverFloor f;
    f.s.scene.light.aoRadius = 3.0;
    f.settings.shadows = false;
    f.settings.aoSamples = 64;
    f.settings.aoError = 0.03;
    const auto frame = render(f.s, f.settings);
    const Image& img = frame.image;
    const int ao = img.channelIndex("ao");
    int pixels = 0, outside = 0, allOpen = 0;
    double expectedAllOpen = 0.0;
    f.forEachFloorPixelUnderTheSphere(
        img, [&](int x, int y, const glm::dvec3&, double d, double cosBeta) {
            const double closed = (f.radius / d) * (f.radius / d) * cosBeta;
            const double expected = 1.0 - closed;
            expectedAllOpen += allAlikeBound(closed);
            ++pixels;
            if (img.at(x, y, ao) == 1.0f) {
                ++allOpen;
                return;
            }
            const double se = std::max(0.03, std::sqrt(expected * (1.0 - expected) / 256.0));
            outside += std::abs(img.at(x, y, ao) - expected) > 4.0 * se + 1e-3;
        });
    ASSERT_GT(pixels, 1000);
    expectWithinTheTarget(outside, allOpen, expectedAllOpen, frame, "ao", 0.03);
}

TEST(RaymarchRounds, LightOfAGlowingSphereMatchesTheClosedFormWithinItsTarget) {
    // The glowing sphere over the floor
    // (Raymarch.LightOfAGlowingSphereOnAFloorMatchesTheClosedForm) with raymarch.emissive_error =
    // 0.05 (luminance) and 64 samples. A channel's error is the luminance's times radiance_k /
    // luminance(radiance) (one colour); at the cap of 256 it is at most solidAngle L_k / (2
    // sqrt(256)): within 4 of the larger of the two. The sphere fills the share q = (1 - cos(asin(r
    // / d))) / (1 - cos(asin(0.8 / d))) of the cone about its support that the reference samples,
    // so a pixel that holds exactly 0 is one whose 16 first directions all missed it: as many as
    // allAlikeBound lets through.
    SphereOverFloor f;
    f.s.scene.light.emissiveLight = true;
    f.s.scene.light.intensity = 0.0;
    f.settings.shadows = false;
    f.settings.emissiveSamples = 64;
    f.settings.emissiveError = 0.05;
    const glm::dvec3 radiance(2.0, 1.0, 0.5);
    f.makeTheSphereGlow(radiance);
    const double luminance = 0.2126 * radiance.r + 0.7152 * radiance.g + 0.0722 * radiance.b;
    const auto frame = render(f.s, f.settings);
    const Image& img = frame.image;
    const int e = img.channelIndex("irradiance.R");
    int pixels = 0, outside = 0, dark = 0;
    double expectedDark = 0.0;
    f.forEachFloorPixelUnderTheSphere(
        img, [&](int x, int y, const glm::dvec3&, double d, double cosBeta) {
            const double share = (1.0 - std::sqrt(1.0 - (f.radius / d) * (f.radius / d))) /
                                 (1.0 - std::sqrt(1.0 - (0.8 / d) * (0.8 / d)));
            expectedDark += allAlikeBound(share);
            ++pixels;
            if (img.at(x, y, e) == 0.0f) {
                ++dark;
                return;
            }
            const double geometry = (f.radius / d) * (f.radius / d) * cosBeta;
            for (int k = 0; k < 3; ++k) {
                const double expected = std::numbers::pi * radiance[k] * geometry;
                const double se = std::max(0.05 * radiance[k] / luminance,
                                           f.supportSolidAngle(d) * radiance[k] / (2.0 * 16.0));
                outside += std::abs(img.at(x, y, e + k) - expected) > 4.0 * se + 1e-4;
            }
        });
    ASSERT_GT(pixels, 1000);
    expectWithinTheTarget(outside, dark, expectedDark, frame, "irradiance", 0.05);
}

TEST(RaymarchRounds, ASunCastsThePenumbraOfItsQuadratureWithinItsTarget) {
    // The sphere's shadow under a sun of 4 degrees (Raymarch.ASunWithAnAngularRadiusCasts-
    // ThePenumbra) with raymarch.sun_error = 0.03 and 64 samples. The truth of a floor point:
    // the share of the sun's directions (uniform in solid angle over its disc) whose ray
    // misses the sphere, by a 96 x 96 midpoint quadrature of the disc. Wholly lit points hold
    // exactly 1, wholly shadowed ones 0; in the penumbra within 4 of the larger of the target
    // and the binomial bound of 256 directions, except those whose 16 first directions agree
    // (allAlikeBound).
    SphereOverFloor f;
    f.s.scene.light.angularRadiusDeg = 4.0;
    f.settings.sunSamples = 64;
    f.settings.sunError = 0.03;
    const double sun = 4.0 * std::numbers::pi / 180.0;
    const auto frame = render(f.s, f.settings);
    const Image& img = frame.image;
    glm::dvec3 u, v;
    tr::raymarch::orthonormalBasis(f.toLight, u, v);
    const double oneMinusCos = 1.0 - std::cos(sun);
    const auto visibleShare = [&](const glm::dvec3& p) {
        const int side = 96;
        const glm::dvec3 toCentre = glm::normalize(f.centre - p);
        const double cosSphere = std::cos(std::asin(f.radius / glm::length(f.centre - p)));
        int open = 0;
        for (int i = 0; i < side; ++i)
            for (int j = 0; j < side; ++j) {
                const glm::dvec2 st((i + 0.5) / side, (j + 0.5) / side);
                const glm::dvec3 d = tr::raymarch::coneDirection(f.toLight, u, v, oneMinusCos, st);
                open += glm::dot(d, toCentre) < cosSphere;
            }
        return double(open) / (side * side);
    };
    int lit = 0, umbra = 0, penumbra = 0, wrong = 0, outside = 0, alike = 0;
    double expectedAlike = 0.0;
    f.forEachFloorPixel(img, [&](int x, int y, const glm::dvec3& p, double angle, double pixel) {
        const float got = img.at(x, y, img.channelIndex("shadow"));
        if (angle > sun + pixel) {
            ++lit;
            wrong += got != 1.0f;
        } else if (angle < -sun - pixel) {
            ++umbra;
            wrong += got != 0.0f;
        } else if (std::abs(angle) < sun - pixel) {
            ++penumbra;
            const double truth = visibleShare(p);
            expectedAlike += allAlikeBound(truth) + allAlikeBound(1.0 - truth);
            if (got == 0.0f || got == 1.0f) {
                ++alike;
                return;
            }
            const double se = std::max(0.03, std::sqrt(truth * (1.0 - truth) / 256.0));
            outside += std::abs(got - truth) > 4.0 * se + 1e-3;
        }
    });
    EXPECT_GT(lit, 1000);
    EXPECT_GT(umbra, 20);
    EXPECT_GT(penumbra, 50);
    EXPECT_EQ(wrong, 0);
    expectWithinTheTarget(outside, alike, expectedAlike, frame, "sun", 0.03);
}

TEST(RaymarchRounds, SameImageAndCountersForAnyThreadCount) {
    // Occlusion, the sphere's light and the sun's disc, each in rounds, at 48 x 48: the rounds
    // of a pixel depend on its own seed alone.
    SphereOverFloor f;
    f.s.scene.camera.width = f.s.scene.camera.height = 48;
    f.s.scene.light.aoRadius = 1.0;
    f.s.scene.light.emissiveLight = true;
    f.s.scene.light.angularRadiusDeg = 3.0;
    f.makeTheSphereGlow(glm::dvec3(1.0, 0.8, 0.5));
    f.settings.aoSamples = f.settings.emissiveSamples = f.settings.sunSamples = 16;
    f.settings.aoError = 0.02;
    f.settings.emissiveError = 0.02;
    f.settings.sunError = 0.02;
    const auto one = render(f.s, f.settings, 1);
    const auto two = render(f.s, f.settings, 2);
    ASSERT_EQ(one.image.pixels().size(), two.image.pixels().size());
    EXPECT_EQ(std::memcmp(one.image.pixels().data(), two.image.pixels().data(),
                          one.image.pixels().size() * sizeof(float)),
              0);
    for (const char* kind : {"ao", "irradiance", "sun"})
        for (const std::string counter :
             {"_rays", "_standard_error", "_standard_error_max", "_at_cap"})
            EXPECT_EQ(one.counters.at(kind + counter), two.counters.at(kind + counter))
                << kind << counter;
    EXPECT_GT(one.counters.at("ao_rays"), 0.0);
    EXPECT_GT(one.counters.at("irradiance_rays"), 0.0);
    EXPECT_GT(one.counters.at("sun_rays"), 0.0);
}

TEST(RaymarchRounds, EveryEstimateBelowItsCapIsBelowTheTarget) {
    // The floor's occlusion by the sphere with a cap of 4096 directions (ao_samples = 1024)
    // that no estimate reaches at a target of 0.01: the largest standard error of the frame
    // is below it. With a target below anything 64 directions can state (a cap of 64: one
    // ray unlike the others in a parent of four states 0.0156), every estimate with a
    // spread stops at the cap: the frame counts them, and its largest error is above the
    // target; the open ones stop at 16, the fixed count, so the frame takes more rays than
    // the fixed count but fewer than the cap's.
    SphereOverFloor f;
    f.s.scene.camera.width = f.s.scene.camera.height = 32;
    f.s.scene.light.aoRadius = 3.0;
    f.settings.shadows = false;
    f.settings.aoSamples = 1024;
    f.settings.aoError = 0.01;
    const auto reached = render(f.s, f.settings);
    EXPECT_EQ(reached.counters.at("ao_at_cap"), 0.0);
    EXPECT_GT(reached.counters.at("ao_standard_error_max"), 0.0);
    EXPECT_LT(reached.counters.at("ao_standard_error_max"), 0.01);
    f.settings.aoSamples = 16;
    f.settings.aoError = 1e-3;
    const auto capped = render(f.s, f.settings);
    EXPECT_GT(capped.counters.at("ao_at_cap"), 100.0);
    EXPECT_GT(capped.counters.at("ao_standard_error_max"), 1e-3);
    f.settings.aoError = 0.0;
    const auto fixed = render(f.s, f.settings);
    EXPECT_GT(capped.counters.at("ao_rays"), fixed.counters.at("ao_rays"));
    EXPECT_LT(capped.counters.at("ao_rays"), 4.0 * fixed.counters.at("ao_rays"));
}
