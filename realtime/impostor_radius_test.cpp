#include "realtime/impostor_radius.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/vec3.hpp>

#include "core/sph_kernel.h"

namespace twinrender::realtime {
namespace {

core::ParticleSet lone(float h) {
    core::ParticleSet ps;
    ps.resize(1);
    ps.position[0] = {1.0f, -2.0f, 0.5f};
    ps.h[0] = h;
    ps.volume[0] = static_cast<float>(core::maxParticleVolume(double(h)));
    ps.normal[0] = {0.0f, 0.0f, 1.0f};
    return ps;
}

// A lone particle's level set is the sphere where v W(r, h) = level: the field radius finds it
// (to the bisection's 1e-4 h), whatever the crossing scale (which is for the level set bulging
// between neighbours).
TEST(ImpostorRadius, ALoneParticleGetsItsLevelSetDroplet) {
    const float h = 0.5f;
    const core::ParticleSet ps = lone(h);
    ParticleSettings s;
    s.crossingScale = 1.0;
    const double v = ps.volume[0];
    double lo = 0.0, hi = h;  // v W(r, h) falls through the level between 0 and h
    for (int k = 0; k < 60; ++k) {
        const double r = 0.5 * (lo + hi);
        (v * core::m4Kernel(r, double(h)) > s.surfaceLevel ? lo : hi) = r;
    }
    const std::vector<float> r = impostorRadii(ps, s);
    EXPECT_NEAR(r[0], lo, 2e-4 * h);
    EXPECT_LT(r[0], 0.15 * h);  // about 0.13 h: far smaller than the fixed 0.9 h
    s.crossingScale = 1.2;
    EXPECT_NEAR(impostorRadii(ps, s)[0], lo, 2e-4 * h);
    s.radius = RadiusModel::Fixed;
    EXPECT_FLOAT_EQ(impostorRadii(ps, s)[0], 0.9f * h);
}

// A particle whose field is below the level everywhere has no surface: radius 0 (not drawn).
TEST(ImpostorRadius, NoSurfaceNoRadius) {
    core::ParticleSet ps = lone(0.5f);
    ps.volume[0] *= 0.5f;  // v W(0, h) = 0.067 < 0.13
    EXPECT_EQ(impostorRadii(ps, ParticleSettings{})[0], 0.0f);
}

// Inside a flat lattice the level set lies beyond the cap: the top layer keeps radius_scale h.
TEST(ImpostorRadius, ALatticeSurfaceKeepsTheCap) {
    core::ParticleSet ps;
    const int n = 7;
    const float s = 0.1f;
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                ps.position.emplace_back(x * s, y * s, z * s);
                ps.h.push_back(1.3f * s);
                ps.volume.push_back(s * s * s);
                ps.normal.emplace_back(0.0f, 0.0f, 1.0f);
            }
    const std::size_t centreTop = (2 * n + 3) * n + 3;
    const std::vector<float> r = impostorRadii(ps, ParticleSettings{});
    EXPECT_FLOAT_EQ(r[centreTop], 0.9f * 1.3f * s);
}

// Two particles 1.5 h apart: each one's crossing along its outward normal, times the crossing
// scale (their level set bulges between them beyond the spheres of the crossings).
core::ParticleSet pair(float h) {
    core::ParticleSet ps = lone(h);
    ps.resize(2);
    ps.position[1] = ps.position[0] + glm::vec3(1.5f * h, 0.0f, 0.0f);
    ps.h[1] = h;
    ps.volume[1] = ps.volume[0];
    ps.normal[0] = {-1.0f, 0.0f, 0.0f};
    ps.normal[1] = {1.0f, 0.0f, 0.0f};
    return ps;
}

TEST(ImpostorRadius, NeighboursGetTheCrossingScale) {
    const core::ParticleSet ps = pair(0.5f);
    ParticleSettings s;
    s.crossingScale = 1.0;
    const std::vector<float> plain = impostorRadii(ps, s);
    EXPECT_GT(plain[0], impostorRadii(lone(0.5f), s)[0]);  // the neighbour's field adds
    s.crossingScale = 1.2;
    const std::vector<float> scaled = impostorRadii(ps, s);
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(scaled[i], 1.2f * plain[i], 1e-5f);
}

// interior_level: a particle whose field at its centre is at least that takes the cap without
// the search along its normal (here against a crossing well inside the cap); a lone particle
// keeps its droplet whatever the level.
TEST(ImpostorRadius, AParticleAtTheInteriorLevelTakesTheCap) {
    const float h = 0.5f;
    const core::ParticleSet ps = pair(h);
    ParticleSettings s;
    const float searched = impostorRadii(ps, s)[0];
    const float cap = static_cast<float>(s.radiusScale * h);
    ASSERT_LT(searched, 0.5f * cap);
    const double atCentre = core::ColourField(ps).value(glm::dvec3(ps.position[0]));
    s.interiorLevel = atCentre;
    EXPECT_FLOAT_EQ(impostorRadii(ps, s)[0], cap);
    s.interiorLevel = std::nextafter(atCentre, 1e9);
    EXPECT_EQ(impostorRadii(ps, s)[0], searched);
    s.interiorLevel = 1e-6;
    const core::ParticleSet one = lone(h);
    EXPECT_EQ(impostorRadii(one, s)[0], impostorRadii(one, ParticleSettings{})[0]);
    // Below the surface level there is no surface, whatever interior_level says.
    core::ParticleSet faint = ps;
    for (float& v : faint.volume) v *= 0.5f;
    ASSERT_LT(core::ColourField(faint).value(glm::dvec3(faint.position[0])), s.surfaceLevel);
    EXPECT_EQ(impostorRadii(faint, s)[0], 0.0f);
}

TEST(ImpostorRadius, TheCacheReusesItsAnswerOnlyForTheSameInputs) {
    core::ParticleSet ps = pair(0.5f);
    ImpostorRadiusCache cache;
    ParticleSettings s;
    const float first = cache.radii(ps, s)[0];
    EXPECT_FALSE(cache.reused());
    EXPECT_EQ(cache.radii(ps, s)[0], first);
    EXPECT_TRUE(cache.reused());
    s.crossingScale = 1.0;
    EXPECT_LT(cache.radii(ps, s)[0], first);
    EXPECT_FALSE(cache.reused());
    s.interiorLevel = 1e-6;
    EXPECT_GT(cache.radii(ps, s)[0], first);
    EXPECT_FALSE(cache.reused());
    ps.position[0].x += 1.0f;
    cache.radii(ps, s);
    EXPECT_FALSE(cache.reused());
}

}  // namespace
}  // namespace twinrender::realtime
