// The reference must be right before anything is compared to it: analytic cases.
#include "raymarch/renderer.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "core/atmosphere.h"
#include "core/camera.h"
#include "core/sph_kernel.h"
#include "raymarch/testing/ray_field_testing.h"
#include "raymarch/testing/renderer_scenes.h"

namespace tr = twinrender;

using tr::core::Image;
using tr::raymarch::testing::render;
using tr::raymarch::testing::singleParticleRadius;
using tr::raymarch::testing::SphereOverFloor;
using tr::raymarch::testing::TestScene;

TEST(Raymarch, OneParticleIsASphereOfTheAnalyticRadius) {
    TestScene s;
    const float h = 0.5f;
    const float v = tr::core::maxParticleVolume(h);
    s.addBody({glm::vec3(0.0f)}, h, v);
    tr::raymarch::Settings settings;
    settings.surfaceLevel = 0.6 * v * tr::core::m4Kernel(0.0, double(h));
    settings.shadows = false;
    const double radius = singleParticleRadius(v, h, settings.surfaceLevel);
    s.scene.camera.position = {0.0, 0.0, 3.0};
    s.scene.camera.target = {0.0, 0.0, 0.0};
    s.scene.camera.up = {0.0, 1.0, 0.0};
    s.scene.camera.fovYDeg = 20.0;
    s.scene.camera.width = s.scene.camera.height = 64;
    const auto frame = render(s, settings);
    const Image& img = frame.image;
    const int cZ = img.channelIndex("Z"), cN = img.channelIndex("N.X"), cA = img.channelIndex("A");
    tr::core::Camera camera(s.scene.camera);
    int covered = 0, expected = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const auto ray = camera.ray(x + 0.5, y + 0.5);
            // Analytic ray-sphere intersection.
            const double b = glm::dot(ray.origin, ray.direction);
            const double c = glm::dot(ray.origin, ray.origin) - radius * radius;
            const double disc = b * b - c;
            const bool hits = disc > 0.0;
            expected += hits;
            covered += img.at(x, y, cA) > 0.5f;
            if (!hits || disc < 1e-3) continue;  // skip the rim, where a pixel centre grazes
            const double t = -b - std::sqrt(disc);
            const glm::dvec3 p = ray.origin + t * ray.direction;
            const double z = t * glm::dot(ray.direction, camera.forward());
            EXPECT_NEAR(img.at(x, y, cZ), z, 1e-4 * h + 1e-6) << x << "," << y;
            const glm::dvec3 n = glm::normalize(p);
            const glm::dvec3 got(img.at(x, y, cN), img.at(x, y, cN + 1), img.at(x, y, cN + 2));
            EXPECT_GT(glm::dot(n, got), std::cos(1e-3)) << x << "," << y;  // within 0.06 degrees
        }
    EXPECT_EQ(covered, expected);
    EXPECT_EQ(frame.counters.at("unbracketed_rays"), 0.0);
}

TEST(Raymarch, LatticeHalfSpaceIsFlatAtTheComputedHeight) {
    // A cubic lattice filling z <= 0 over a wide square: the surface above its middle is
    // flat up to the lattice's own ripple. Its height is computed here by brute force: the
    // field summed over every particle, bisected along the vertical line.
    TestScene s;
    const float spacing = 0.1f, h = 1.3f * spacing;
    const float v = std::min(spacing * spacing * spacing, float(tr::core::maxParticleVolume(h)));
    std::vector<glm::vec3> positions;
    for (int i = -20; i <= 20; ++i)
        for (int j = -20; j <= 20; ++j)
            for (int k = 0; k < 6; ++k)
                positions.emplace_back(i * spacing, j * spacing, -k * spacing);
    s.addBody(positions, h, v);
    auto field = [&](glm::dvec3 p) {
        double sum = 0.0;
        for (const auto& x : positions)
            sum += v * tr::core::m4Kernel(glm::length(p - glm::dvec3(x)), double(h));
        return sum;
    };
    tr::raymarch::Settings settings;
    settings.shadows = false;
    s.scene.camera.position = {0.0, 0.0, 2.0};
    s.scene.camera.target = {0.0, 0.0, 0.0};
    s.scene.camera.up = {0.0, 1.0, 0.0};
    s.scene.camera.fovYDeg = 10.0;
    s.scene.camera.width = s.scene.camera.height = 33;
    const auto frame = render(s, settings);
    tr::core::Camera camera(s.scene.camera);
    const Image& img = frame.image;
    for (auto [x, y] : {std::pair{16, 16}, std::pair{5, 9}, std::pair{27, 20}}) {
        const auto ray = camera.ray(x + 0.5, y + 0.5);
        // Bisect along the ray itself, so the comparison is point for point.
        double lo = 0.0, hi = 2.05;  // z = -0.05: inside the top layers
        ASSERT_GT(field(ray.origin + hi * ray.direction), settings.surfaceLevel);
        for (int i = 0; i < 100; ++i) {
            const double mid = 0.5 * (lo + hi);
            (field(ray.origin + mid * ray.direction) < settings.surfaceLevel ? lo : hi) = mid;
        }
        const double z = lo * glm::dot(ray.direction, camera.forward());
        EXPECT_NEAR(img.at(x, y, img.channelIndex("Z")), z, 1e-4 * h) << x << "," << y;
        // The surface of a half-space faces up.
        EXPECT_GT(img.at(x, y, img.channelIndex("N.Z")), 0.99f);
    }
    // The lattice surface lies 0.9 h to 1 h above the top layer (OpenSPH's level 0.13).
    const double centreZ = 2.0 - img.at(16, 16, img.channelIndex("Z"));
    EXPECT_GT(centreZ, 0.85 * h);
    EXPECT_LT(centreZ, 1.0 * h);
}

TEST(Raymarch, SphereShadowOnAPlaneMatchesTheAnalyticOutline) {
    // A floor point is in shadow exactly when the line from it toward the light passes within
    // the sphere's radius of its centre.
    const SphereOverFloor f;
    ASSERT_GT(f.radius, 0.05);
    const auto frame = render(f.s, f.settings);
    const Image& img = frame.image;
    int checked = 0, wrong = 0, shadowed = 0;
    f.forEachFloorPixel(img, [&](int x, int y, const glm::dvec3&, double angle, double pixel) {
        if (std::abs(angle) < pixel) return;  // the outline itself
        const bool inShadow = img.at(x, y, img.channelIndex("shadow")) < 0.5f;
        wrong += inShadow != (angle < 0.0);
        shadowed += inShadow;
        ++checked;
    });
    EXPECT_GT(checked, 2000);
    EXPECT_GT(shadowed, 50);
    EXPECT_EQ(wrong, 0);
}

TEST(Raymarch, ASunWithAnAngularRadiusCastsTheAnalyticPenumbra) {
    // A sun of 4 degrees: a floor point sees all of it (visibility 1) when the sphere's disc
    // and the sun's do not overlap, none of it (0) when the sphere's covers the sun's, part of
    // it between: the penumbra. The same image on every thread count.
    SphereOverFloor f;
    f.s.scene.light.angularRadiusDeg = 4.0;
    f.settings.sunSamples = 32;
    const double sun = 4.0 * std::numbers::pi / 180.0;
    const auto frame = render(f.s, f.settings);
    const Image& img = frame.image;
    int lit = 0, umbra = 0, penumbra = 0, fractional = 0, wrong = 0;
    f.forEachFloorPixel(img, [&](int x, int y, const glm::dvec3&, double angle, double pixel) {
        const float v = img.at(x, y, img.channelIndex("shadow"));
        if (angle > sun + pixel) {
            ++lit;
            wrong += v != 1.0f;
        } else if (angle < -sun - pixel) {
            ++umbra;
            wrong += v != 0.0f;
        } else if (std::abs(angle) < sun - pixel) {
            ++penumbra;
            fractional += v > 0.0f && v < 1.0f;
        }
    });
    EXPECT_GT(lit, 1000);
    EXPECT_GT(umbra, 20);
    EXPECT_GT(penumbra, 50);
    EXPECT_EQ(wrong, 0);
    EXPECT_EQ(fractional, penumbra);
    const auto one = render(f.s, f.settings, 1);
    for (std::size_t p = 0; p < img.pixelCount(); ++p)
        ASSERT_EQ(img.at(p, img.channelIndex("shadow")),
                  one.image.at(p, img.channelIndex("shadow")));
}

TEST(Raymarch, AmbientOcclusionOfAFloorByASphereMatchesTheClosedForm) {
    // A floor point p under a sphere (centre c at distance d, radius r) wholly above its
    // horizon: the sphere closes the cosine-weighted share (r / d)^2 cos(beta) of the
    // hemisphere (the form factor of a differential area to a sphere), beta the angle between
    // the normal and c - p. With the reach longer than any ray to the sphere (at most the
    // tangent length sqrt(d^2 - r^2)) the open fraction is 1 - (r / d)^2 cos(beta); the floor
    // closes nothing above its own plane. Checked per pixel within its own standard error
    // (64 stratified directions), and in the mean within the mean's.
    SphereOverFloor f;
    f.s.scene.light.aoRadius = 3.0;
    f.settings.shadows = false;
    f.settings.aoSamples = 64;
    const auto frame = render(f.s, f.settings);
    const Image& img = frame.image;
    const int ao = img.channelIndex("ao"), nx = img.channelIndex("N.X");
    int pixels = 0, outside = 0;
    double sum = 0.0, variance = 0.0;
    f.forEachFloorPixelUnderTheSphere(
        img, [&](int x, int y, const glm::dvec3&, double d, double cosBeta) {
            const double expected = 1.0 - (f.radius / d) * (f.radius / d) * cosBeta;
            const double error = img.at(x, y, ao) - expected;
            const double se = std::sqrt(expected * (1.0 - expected) / 64.0);
            outside += std::abs(error) > 4.0 * se + 1e-3;
            sum += error;
            variance += se * se;
            ++pixels;
        });
    ASSERT_GT(pixels, 1000);
    EXPECT_EQ(outside, 0);
    const double meanError = sum / pixels, meanSe = std::sqrt(variance) / pixels;
    EXPECT_LT(std::abs(meanError), 4.0 * meanSe + 1e-4) << meanError << " " << meanSe;
    EXPECT_GT(frame.counters.at("ao_standard_error"), 0.0);
    EXPECT_LE(frame.counters.at("ao_standard_error"), 0.5 / 8.0);
    EXPECT_GT(frame.timingsMs.at("ao"), 0.0);
    // The sphere's top: a point whose normal is within 6 degrees of the vertical sees the
    // floor below its horizon in the cosine-weighted share (1 - cos 6 deg) / 2 < 0.003 of its
    // hemisphere: open within a 64th.
    int tops = 0;
    for (std::size_t q = 0; q < img.pixelCount(); ++q)
        if (img.at(q, img.channelIndex("id")) == 1.0f && img.at(q, nx + 2) > 0.9945f) {
            ++tops;
            EXPECT_GE(img.at(q, ao), 1.0f - 1.0f / 64.0f);
        }
    EXPECT_GT(tops, 5);
    // The same image on every thread count.
    const auto one = render(f.s, f.settings, 1);
    for (std::size_t q = 0; q < img.pixelCount(); ++q)
        ASSERT_EQ(img.at(q, ao), one.image.at(q, ao));
}

TEST(Raymarch, AmbientOcclusionReachesOnlyItsRadius) {
    // With a reach shorter than the gap between floor and sphere (d - r > R everywhere), no
    // ray meets the sphere: the floor is open everywhere. Without a reach, no rays are traced
    // and every covered pixel is open.
    SphereOverFloor f;
    f.settings.shadows = false;
    f.settings.aoSamples = 16;
    for (const double reach : {0.0, 0.3}) {
        f.s.scene.light.aoRadius = reach;
        const auto frame = render(f.s, f.settings);
        const Image& img = frame.image;
        int covered = 0;
        for (std::size_t q = 0; q < img.pixelCount(); ++q) {
            if (img.at(q, img.channelIndex("A")) == 0.0f) continue;
            ++covered;
            ASSERT_EQ(img.at(q, img.channelIndex("ao")), 1.0f) << reach;
        }
        EXPECT_GT(covered, 3000);
        EXPECT_EQ(frame.counters.count("ao_rays"), reach > 0.0 ? 1u : 0u);
    }
}

TEST(Raymarch, LightOfAGlowingSphereOnAFloorMatchesTheClosedForm) {
    // A sphere (radius r, centre c) of uniform radiance L over a floor point p, wholly above
    // its horizon: the irradiance there is E = pi L (r / d)^2 cos(beta), d = |c - p|, beta the
    // angle between the normal and c - p (the sphere's form factor times pi L). The reference
    // samples the cone of the sphere around the ball's supports; each sample weighs at most
    // solidAngle / N x L, so its standard error is at most solidAngle L / (2 sqrt(N)). Checked
    // per pixel within 4 of those, in the mean within 4 of the mean's, and the same image on
    // every thread count.
    SphereOverFloor f;
    f.s.scene.light.emissiveLight = true;
    f.s.scene.light.intensity = 0.0;
    f.settings.shadows = false;
    f.settings.emissiveSamples = 64;
    const glm::dvec3 radiance(2.0, 1.0, 0.5);
    f.makeTheSphereGlow(radiance);
    const auto frame = render(f.s, f.settings);
    const Image& img = frame.image;
    const int e = img.channelIndex("irradiance.R");
    int pixels = 0, outside = 0;
    double sum = 0.0, variance = 0.0;
    f.forEachFloorPixelUnderTheSphere(
        img, [&](int x, int y, const glm::dvec3&, double d, double cosBeta) {
            const double geometry = (f.radius / d) * (f.radius / d) * cosBeta;
            const double solidAngle = f.supportSolidAngle(d);
            for (int k = 0; k < 3; ++k) {
                const double expected = std::numbers::pi * radiance[k] * geometry;
                const double error = img.at(x, y, e + k) - expected;
                const double se = solidAngle * radiance[k] / (2.0 * 8.0);
                outside += std::abs(error) > 4.0 * se + 1e-4;
                if (k == 0) {
                    sum += error;
                    variance += se * se;
                }
            }
            ++pixels;
        });
    ASSERT_GT(pixels, 1000);
    EXPECT_EQ(outside, 0);
    const double meanError = sum / pixels, meanSe = std::sqrt(variance) / pixels;
    EXPECT_LT(std::abs(meanError), 4.0 * meanSe + 1e-4) << meanError << " " << meanSe;
    EXPECT_GT(frame.counters.at("irradiance_standard_error"), 0.0);
    EXPECT_EQ(frame.counters.at("emitting_bodies"), 1.0);
    EXPECT_GT(frame.timingsMs.at("emissive"), 0.0);
    // The floor's beauty is its Lambert reflection of that light: albedo E / pi (the sun off,
    // the ambient 0.03 of the white albedo 0.8 on top).
    const int r = img.channelIndex("R");
    int shaded = 0;
    for (std::size_t q = 0; q < img.pixelCount(); ++q)
        if (img.at(q, img.channelIndex("id")) == 0.0f && img.at(q, e) > 0.1f) {
            const double expected = 0.8 * img.at(q, e) / std::numbers::pi + 0.8 * 0.03;
            EXPECT_NEAR(img.at(q, r), expected, 1e-5 * expected);
            ++shaded;
        }
    EXPECT_GT(shaded, 100);
    // The same image on every thread count.
    const auto one = render(f.s, f.settings, 1);
    for (std::size_t q = 0; q < img.pixelCount(); ++q) ASSERT_EQ(img.at(q, e), one.image.at(q, e));
}

TEST(Raymarch, AnOccluderBetweenEmitterAndFloorCastsNoLight) {
    // The glowing sphere with an opaque square slab between it and the floor: a floor point
    // from which every line to the sphere crosses the slab receives nothing; one from which
    // none does receives light.
    SphereOverFloor f;
    f.s.scene.light.emissiveLight = true;
    f.settings.shadows = false;
    // 64: the first of the 8 rings of strata about the cone's axis is the central eighth of
    // the cone, which the sphere covers, so a point that sees the sphere never draws 0.
    f.settings.emissiveSamples = 64;
    f.makeTheSphereGlow(glm::dvec3(1.0));
    // One layer of particles at z = 0.45, |x|, |y| <= 0.3, between the ball (bottom 1 - r)
    // and the floor (0); its surface reaches about h past its particles. Seen from the side,
    // below the slab, so that the floor under it shows.
    f.s.scene.camera.position = {3.0, 0.01, 0.3};
    f.s.scene.camera.target = {0.0, 0.0, 0.0};
    f.s.scene.camera.up = {0.0, 0.0, 1.0};
    f.s.scene.camera.fovYDeg = 20.0;
    const float spacing = 0.1f, h = 1.3f * spacing, height = 0.45f;
    std::vector<glm::vec3> slab;
    for (int i = -3; i <= 3; ++i)
        for (int j = -3; j <= 3; ++j) slab.emplace_back(i * spacing, j * spacing, height);
    f.s.addBody(slab, h,
                std::min(spacing * spacing * spacing, float(tr::core::maxParticleVolume(h))));
    const auto frame = render(f.s, f.settings);
    const Image& img = frame.image;
    const int e = img.channelIndex("irradiance.R");
    // The largest |x|, |y| where the lines from p to the sphere cross the slab's plane.
    const auto reach = [&](const glm::dvec3& p) {
        double lo = INFINITY, hi = 0.0;
        for (int i = 0; i < 24; ++i)
            for (int j = 0; j <= 12; ++j) {
                const double phi = 2.0 * std::numbers::pi * i / 24,
                             theta = std::numbers::pi * j / 12;
                const glm::dvec3 q =
                    f.centre + f.radius * glm::dvec3(std::sin(theta) * std::cos(phi),
                                                     std::sin(theta) * std::sin(phi),
                                                     std::cos(theta));
                const glm::dvec3 x = p + (height - p.z) / (q.z - p.z) * (q - p);
                const double m = std::max(std::abs(x.x), std::abs(x.y));
                lo = std::min(lo, m);
                hi = std::max(hi, m);
            }
        return std::pair{lo, hi};
    };
    int dark = 0, lit = 0;
    f.forEachFloorPixel(img, [&](int x, int y, const glm::dvec3& p, double, double) {
        const auto [lo, hi] = reach(p);
        if (hi < 0.3 - 0.05) {  // every line crosses the slab well inside its edge
            ++dark;
            EXPECT_EQ(img.at(x, y, e), 0.0f) << x << " " << y;
        } else if (lo > 0.3 + 2.0 * h) {  // no line comes near it
            ++lit;
            EXPECT_GT(img.at(x, y, e), 0.0f) << x << " " << y;
        }
    });
    EXPECT_GT(dark, 20);
    EXPECT_GT(lit, 50);
}

TEST(Raymarch, SameImageForAnyThreadCount) {
    TestScene s;
    std::vector<glm::vec3> positions;
    std::uint32_t state = 12345;
    auto next = [&] {
        state = state * 1664525u + 1013904223u;
        return (state >> 8) / 16777216.0f;
    };
    for (int i = 0; i < 3000; ++i) {
        glm::vec3 p(next() * 2 - 1, next() * 2 - 1, next() * 2 - 1);
        if (glm::length(p) < 1.0f) positions.push_back(p);
    }
    s.addBody(positions, 0.15f, float(tr::core::maxParticleVolume(0.15)));
    s.scene.camera.position = {0.3, -3.0, 1.0};
    s.scene.camera.target = {0.0, 0.0, 0.0};
    s.scene.camera.width = 48;
    s.scene.camera.height = 40;
    s.scene.light.direction = glm::normalize(glm::dvec3(-1.0, 0.5, -0.7));
    tr::raymarch::Settings settings;
    settings.spp = 4;
    const auto one = render(s, settings, 1);
    const auto two = render(s, settings, 2);
    const auto twoAgain = render(s, settings, 2);
    // Tiles smaller than a pixel block cut the blocks at the tile's edge: one writer per pixel
    // still, and the same surface.
    tr::raymarch::Settings smallTiles = settings;
    smallTiles.tileSize = 4;
    const auto smallOne = render(s, smallTiles, 1);
    const auto smallTwo = render(s, smallTiles, 2);
    auto firstDifference = [](const Image& a, const Image& b) -> std::string {
        for (std::size_t p = 0; p < a.pixelCount(); ++p)
            for (int c = 0; c < a.channelCount(); ++c)
                if (const float x = a.at(p, c), y = b.at(p, c);
                    std::memcmp(&x, &y, sizeof(float)) != 0)
                    return a.channelNames()[c] + " at pixel " + std::to_string(p % a.width()) +
                           "," + std::to_string(p / a.width()) + ": " + std::to_string(a.at(p, c)) +
                           " vs " + std::to_string(b.at(p, c));
        return "";
    };
    EXPECT_EQ(firstDifference(one.image, two.image), "");
    EXPECT_EQ(firstDifference(two.image, twoAgain.image), "");
    EXPECT_EQ(firstDifference(smallOne.image, smallTwo.image), "");
    // The display image, written with each pixel, is the frame's tonemapped beauty.
    EXPECT_EQ(firstDifference(one.display, tr::core::tonemappedBeauty(one.image, 1.0f)), "");
    EXPECT_EQ(firstDifference(one.display, two.display), "");
    double smallCoverage = 0.0;
    for (std::size_t p = 0; p < smallOne.image.pixelCount(); ++p)
        smallCoverage += smallOne.image.at(p, smallOne.image.channelIndex("A"));
    // Something was drawn, and shadows too.
    double coverage = 0.0, lit = 0.0;
    for (std::size_t p = 0; p < one.image.pixelCount(); ++p) {
        coverage += one.image.at(p, one.image.channelIndex("A"));
        lit += one.image.at(p, one.image.channelIndex("shadow"));
    }
    EXPECT_GT(coverage, 200.0);
    EXPECT_LT(lit, coverage);
    // Other blocks start their searches from other neighbours' crossings; the hits agree.
    EXPECT_NEAR(smallCoverage, coverage, 0.5);
}

namespace {

// One particle (a perfect sphere of the analytic radius) seen from z = 3, lit from above, with
// an atmosphere whose inner sphere is that radius; camera 64 x 64.
struct AtmosphereScene {
    TestScene s;
    tr::raymarch::Settings settings;
    double radius = 0.0;

    explicit AtmosphereScene(glm::dvec3 scattering) {
        const float h = 0.5f;
        const float v = tr::core::maxParticleVolume(h);
        s.addBody({glm::vec3(0.0f)}, h, v);
        settings.surfaceLevel = 0.6 * v * tr::core::m4Kernel(0.0, double(h));
        settings.shadows = false;
        radius = singleParticleRadius(v, h, settings.surfaceLevel);
        s.scene.camera.position = {0.0, 0.4, 3.0};
        s.scene.camera.target = {0.0, 0.0, 0.0};
        s.scene.camera.up = {0.0, 1.0, 0.0};
        s.scene.camera.fovYDeg = 30.0;
        s.scene.camera.width = s.scene.camera.height = 64;
        s.scene.light.direction = glm::normalize(glm::dvec3(-1.0, -0.3, -0.5));
        tr::core::BodyDesc body;
        body.atmosphere = tr::core::AtmosphereDesc{.thickness = 0.4,
                                                   .scaleHeight = 0.15,
                                                   .scattering = scattering,
                                                   .absorption = 0.2 * scattering,
                                                   .phaseG = 0.3,
                                                   .radius = radius,
                                                   .steps = 16};
        s.scene.bodies.push_back(body);
    }
};

}  // namespace

// On a perfect sphere the exact hit is the analytic sphere's: the reference's in-scatter is
// the model's (core/atmosphere.h) ended there, on the sky pixels too, and the beauty holds it.
TEST(Raymarch, InScatterOnAPerfectSphereIsTheModelEndedAtTheAnalyticHit) {
    const AtmosphereScene a({1.0, 2.0, 4.0});
    const auto frame = render(a.s, a.settings);
    const Image& img = frame.image;
    const int cS = img.channelIndex("inscatter.R"), cA = img.channelIndex("A");
    const auto atmosphere =
        tr::core::sceneAtmosphere(a.s.scene, a.s.particles, a.settings.surfaceLevel);
    ASSERT_TRUE(atmosphere);
    const tr::core::AtmosphereSun sun = tr::core::atmosphereSun(a.s.scene.light);
    const tr::core::Camera camera(a.s.scene.camera);
    int sky = 0, surface = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const auto ray = camera.ray(x + 0.5, y + 0.5);
            const glm::vec3 origin(ray.origin - atmosphere->centre), direction(ray.direction);
            const float end = tr::core::sphereEntry(origin, direction, float(a.radius));
            // Skip the rim, where a pixel centre grazes the sphere and a root refined to
            // 1e-4 h moves the end point along the ray by far more.
            const glm::dvec3 closest =
                ray.origin - glm::dot(ray.origin, ray.direction) * ray.direction;
            if (std::abs(glm::length(closest) - a.radius) < 0.02) continue;
            const glm::vec3 expected =
                tr::core::integrateAtmosphere(*atmosphere, sun, origin, direction, end).inscatter;
            (std::isinf(end) ? sky : surface) += expected.b > 0.0f;
            for (int k = 0; k < 3; ++k)
                // The root to 1e-4 h moves the end point by as much: the in-scatter by at most
                // sigma_s p E there, about 1e-4 of it; the rest is float rounding.
                EXPECT_NEAR(img.at(x, y, cS + k), expected[k], 1e-3f * expected[k] + 1e-6f)
                    << x << "," << y;
            if (std::isinf(end)) {
                EXPECT_EQ(img.at(x, y, cA), 0.0f);
                EXPECT_FLOAT_EQ(img.at(x, y, 2), expected.b);  // the sky's beauty
            }
        }
    EXPECT_GT(sky, 200);
    EXPECT_GT(surface, 200);
    EXPECT_GT(frame.timingsMs.count("atmosphere"), 0u);
}

// An atmosphere that neither scatters nor absorbs changes no channel of the frame, bit for
// bit: every other frame is what it was before atmospheres.
TEST(Raymarch, AnEmptyAtmosphereChangesNothing) {
    AtmosphereScene a(glm::dvec3(0.0));
    a.settings.spp = 4;
    const auto with = render(a.s, a.settings);
    a.s.scene.bodies.clear();
    const auto without = render(a.s, a.settings);
    ASSERT_EQ(with.image.pixels().size(), without.image.pixels().size());
    EXPECT_EQ(std::memcmp(with.image.pixels().data(), without.image.pixels().data(),
                          with.image.pixels().size() * sizeof(float)),
              0);
    EXPECT_EQ(std::memcmp(with.display.pixels().data(), without.display.pixels().data(),
                          with.display.pixels().size() * sizeof(float)),
              0);
    EXPECT_EQ(without.timingsMs.count("atmosphere"), 0u);
}
