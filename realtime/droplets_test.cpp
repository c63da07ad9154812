#include "realtime/droplets.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "core/colour_field.h"
#include "realtime/impostor_radius.h"

namespace twinrender::realtime {
namespace {

constexpr float H = 1.0f;
constexpr double LEVEL = 0.13;

// Particles of smoothing length H at the given positions, with the volume cap of docs/design.md
// (0.1 (4/3) pi h^3, a lone particle's droplet about 0.13 h across at LEVEL) and field radii.
struct Set {
    core::ParticleSet ps;
    std::vector<float> radii;
};
Set particlesAt(const std::vector<glm::vec3>& positions) {
    Set s;
    for (const glm::vec3& p : positions) {
        s.ps.position.push_back(p);
        s.ps.h.push_back(H);
    }
    const std::size_t n = positions.size();
    s.ps.volume.assign(n, static_cast<float>(0.1 * 4.0 / 3.0 * std::numbers::pi * H * H * H));
    s.ps.body.assign(n, 0);
    // The field's gradient direction at each particle, as the derived normals are.
    const core::ColourField field(s.ps);
    for (const glm::vec3& p : positions) {
        const glm::dvec3 g = field.derivatives(glm::dvec3(p)).gradient;
        s.ps.normal.push_back(glm::length(g) > 0.0 ? glm::vec3(-glm::normalize(g))
                                                   : glm::vec3(0.0f, 0.0f, 1.0f));
    }
    ParticleSettings settings;
    settings.surfaceLevel = LEVEL;
    s.radii = impostorRadii(s.ps, settings);
    return s;
}

// A 6 x 6 x 6 cubic lattice of spacing 0.77 h (h = 1.3 spacings) about `centre`.
std::vector<glm::vec3> body(const glm::vec3& centre) {
    std::vector<glm::vec3> out;
    for (int z = 0; z < 6; ++z)
        for (int y = 0; y < 6; ++y)
            for (int x = 0; x < 6; ++x)
                out.push_back(centre + H / 1.3f * (glm::vec3(x, y, z) - 2.5f));
    return out;
}

TEST(Droplets, APairIsOneEllipsoidReachingTheLevelSetAlongEachAxis) {
    // 1.2 h apart: the field at the midpoint (2 v W(0.6 h)) is above the level, so the pair's
    // level set is one capsule; each particle's sphere reaches only about 0.27 h.
    const Set s = particlesAt({{0.0f, 0.0f, 0.0f}, {1.2f * H, 0.0f, 0.0f}});
    const Droplets d = fitDroplets(s.ps, s.radii, LEVEL, 8);
    ASSERT_EQ(d.firsts, std::vector<std::uint32_t>{0});
    EXPECT_EQ(d.radii[1], 0.0f);
    EXPECT_EQ(d.cullRadii[0], 0.0f);
    const Ellipsoid& e = d.ellipsoids[0];
    const glm::vec3 centre = s.ps.position[0] + e.shift;
    // Symmetric pair: centred on the midpoint (to the crossings' 1e-4 h resolution, times a
    // few for float rounding).
    EXPECT_NEAR(glm::distance(centre, glm::vec3(0.6f * H, 0.0f, 0.0f)), 0.0f, 1e-3f * H);
    // Every axis end lies on the level set: the field there is the level to within the
    // crossing's resolution times the field's slope (|grad c| < 0.5 / h here).
    const core::ColourField field(s.ps);
    float longest = 0.0f;
    for (const glm::vec3& a : e.axes) {
        for (const float sign : {1.0f, -1.0f})
            EXPECT_NEAR(field.value(glm::dvec3(centre + sign * a)), LEVEL, 1e-3);
        longest = std::max(longest, glm::length(a));
    }
    // The long axis along the pair, reaching where each particle's crossing along its normal
    // (pointing away from the other) does: the same point of the level set.
    EXPECT_GT(std::abs(glm::normalize(e.axes[0]).x), 0.999f);
    const float crossing = s.radii[0] / static_cast<float>(ParticleSettings{}.crossingScale);
    EXPECT_NEAR(longest, 0.6f * H + crossing, 1e-3f * H);
    // Its width at the midpoint is wider than the spheres' union reaches there (not at all:
    // two spheres of 0.27 h with centres 0.6 h from it).
    EXPECT_GT(glm::length(e.axes[1]), 0.3f * H);
    EXPECT_NEAR(d.radii[0],
                std::cbrt(glm::length(e.axes[0]) * glm::length(e.axes[1]) * glm::length(e.axes[2])),
                1e-5f);
}

TEST(Droplets, LoneParticlesAndSeparateDropletsStaySpheres) {
    // 1.6 h apart the midpoint field (2 v W(0.8 h) = 0.11) is below the level: two droplets of
    // one particle each, whose spheres are exact.
    const Set apart = particlesAt({{0.0f, 0.0f, 0.0f}, {1.6f * H, 0.0f, 0.0f}});
    EXPECT_TRUE(fitDroplets(apart.ps, apart.radii, LEVEL, 8).firsts.empty());
    const Set lone = particlesAt({{0.0f, 0.0f, 0.0f}});
    EXPECT_TRUE(fitDroplets(lone.ps, lone.radii, LEVEL, 8).firsts.empty());
}

TEST(Droplets, BodiesAndClustersLargerThanTheLimitStaySpheres) {
    const Set lattice = particlesAt(body(glm::vec3(0.0f)));
    EXPECT_TRUE(fitDroplets(lattice.ps, lattice.radii, LEVEL, 8).firsts.empty());
    // A chain of three 1.1 h apart is one droplet at a limit of 3 atoms, none at 2.
    const Set chain = particlesAt({{0.0f, 0.0f, 0.0f}, {1.1f * H, 0, 0}, {2.2f * H, 0, 0}});
    EXPECT_EQ(fitDroplets(chain.ps, chain.radii, LEVEL, 3).firsts.size(), 1u);
    EXPECT_TRUE(fitDroplets(chain.ps, chain.radii, LEVEL, 2).firsts.empty());
    EXPECT_TRUE(fitDroplets(chain.ps, chain.radii, LEVEL, 0).firsts.empty());
}

TEST(Droplets, APairTouchingABodyIsPartOfIt) {
    // The pair's near particle is 0.9 h beyond the body's last layer: connected to it.
    std::vector<glm::vec3> positions = body(glm::vec3(0.0f));
    const float edge = 2.5f * H / 1.3f;
    positions.push_back({edge + 0.9f * H, 0.0f, 0.0f});
    positions.push_back({edge + 2.1f * H, 0.0f, 0.0f});
    const Set s = particlesAt(positions);
    EXPECT_TRUE(fitDroplets(s.ps, s.radii, LEVEL, 8).firsts.empty());
    // Far from the body it is a droplet again.
    positions[positions.size() - 2].x += 10.0f * H;
    positions.back().x += 10.0f * H;
    const Set far = particlesAt(positions);
    EXPECT_EQ(fitDroplets(far.ps, far.radii, LEVEL, 8).firsts.size(), 1u);
}

TEST(Droplets, TheSameWhateverTheThreadCount) {
    std::vector<glm::vec3> positions;
    for (int k = 0; k < 40; ++k) {
        const glm::vec3 base(5.0f * H * float(k % 7), 5.0f * H * float(k / 7), 0.0f);
        positions.push_back(base);
        positions.push_back(base + glm::vec3(1.0f * H, 0.1f * float(k % 3), 0.0f));
        if (k % 2) positions.push_back(base + glm::vec3(0.5f * H, 0.9f * H, 0.2f));
    }
    const Set s = particlesAt(positions);
    const Droplets all = fitDroplets(s.ps, s.radii, LEVEL, 8);
    Droplets one;
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        one = fitDroplets(s.ps, s.radii, LEVEL, 8);
    }
    ASSERT_EQ(all.firsts.size(), 40u);
    EXPECT_EQ(all.firsts, one.firsts);
    EXPECT_EQ(all.radii, one.radii);
    for (std::uint32_t i : all.firsts)
        for (int a = 0; a < 3; ++a) EXPECT_EQ(all.ellipsoids[i].axes[a], one.ellipsoids[i].axes[a]);
}

TEST(Droplets, TheCacheKeepsTheAnswerForTheSameSet) {
    const Set s = particlesAt({{0.0f, 0.0f, 0.0f}, {1.2f * H, 0.0f, 0.0f}});
    DropletCache cache;
    EXPECT_EQ(cache.droplets(s.ps, s.radii, LEVEL, 8).firsts.size(), 1u);
    EXPECT_FALSE(cache.reused());
    cache.droplets(s.ps, s.radii, LEVEL, 8);
    EXPECT_TRUE(cache.reused());
    EXPECT_TRUE(cache.droplets(s.ps, s.radii, LEVEL, 0).firsts.empty());
    EXPECT_FALSE(cache.reused());
}

}  // namespace
}  // namespace twinrender::realtime
