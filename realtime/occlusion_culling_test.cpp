#include "realtime/occlusion_culling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <random>

#include "realtime/impostor_radius.h"

namespace twinrender::realtime {
namespace {

core::ParticleSet cube(int n, float spacing, float h) {
    core::ParticleSet ps;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                ps.position.emplace_back(x * spacing, y * spacing, z * spacing);
                ps.h.push_back(h);
            }
    return ps;
}

bool contains(const std::vector<std::uint32_t>& v, std::uint32_t i) {
    return std::binary_search(v.begin(), v.end(), i);
}

TEST(OcclusionCulling, KeepsTheSurfaceLayerOfALatticeAndCullsTheInside) {
    const int n = 6;
    const core::ParticleSet ps = cube(n, 1.0f, 1.3f);
    const auto kept = unoccludedParticles(ps, fixedRadii(ps, 0.95));
    ASSERT_TRUE(std::is_sorted(kept.begin(), kept.end()));
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const auto i = static_cast<std::uint32_t>((z * n + y) * n + x);
                const bool boundary =
                    x == 0 || y == 0 || z == 0 || x == n - 1 || y == n - 1 || z == n - 1;
                if (boundary) {
                    EXPECT_TRUE(contains(kept, i)) << x << " " << y << " " << z;
                }
                // Two layers in from every face, a particle has all 6 + 12 close neighbours.
                if (x >= 1 && y >= 1 && z >= 1 && x <= n - 2 && y <= n - 2 && z <= n - 2) {
                    EXPECT_FALSE(contains(kept, i)) << x << " " << y << " " << z;
                }
            }
}

// The defining property, checked by brute force: every point of a culled sphere lies inside
// another sphere.
TEST(OcclusionCulling, CulledSpheresAreCoveredByOthers) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 4.0f), hd(0.5f, 0.9f);
    core::ParticleSet ps;
    for (int i = 0; i < 1500; ++i) {
        ps.position.emplace_back(u(rng), u(rng), u(rng));
        ps.h.push_back(hd(rng));
    }
    const double scale = 0.95;
    const auto kept = unoccludedParticles(ps, fixedRadii(ps, scale));
    std::size_t culled = 0;
    std::normal_distribution<double> g;
    for (std::uint32_t i = 0; i < ps.size(); ++i) {
        if (contains(kept, i)) continue;
        ++culled;
        for (int s = 0; s < 400; ++s) {
            glm::dvec3 d(g(rng), g(rng), g(rng));
            const glm::dvec3 p = glm::dvec3(ps.position[i]) + glm::normalize(d) * (scale * ps.h[i]);
            bool inside = false;
            for (std::uint32_t j = 0; j < ps.size() && !inside; ++j)
                inside = j != i && glm::length(p - glm::dvec3(ps.position[j])) < scale * ps.h[j];
            ASSERT_TRUE(inside) << "particle " << i << " culled but visible";
        }
    }
    EXPECT_GT(culled, 100u);  // the test must exercise culling
}

TEST(OcclusionCulling, EdgeCases) {
    core::ParticleSet one;
    one.position = {{0, 0, 0}};
    one.h = {1.0f};
    EXPECT_EQ(unoccludedParticles(one, fixedRadii(one, 1.0)).size(), 1u);

    // Two equal coincident spheres: one stays. A small sphere inside a big one goes.
    core::ParticleSet ps;
    ps.position = {{0, 0, 0}, {0, 0, 0}, {5, 0, 0}, {5.1f, 0, 0}};
    ps.h = {1.0f, 1.0f, 2.0f, 0.5f};
    EXPECT_EQ(unoccludedParticles(ps, fixedRadii(ps, 1.0)), (std::vector<std::uint32_t>{0, 2}));
}

TEST(OcclusionCulling, TheCullerReusesItsAnswerOnlyForTheSameSpheres) {
    core::ParticleSet ps = cube(5, 1.0f, 1.3f);
    OcclusionCuller culler;
    const auto first = culler.unoccluded(ps, fixedRadii(ps, 0.95));
    EXPECT_FALSE(culler.reused());
    EXPECT_EQ(first, unoccludedParticles(ps, fixedRadii(ps, 0.95)));
    EXPECT_EQ(culler.unoccluded(ps, fixedRadii(ps, 0.95)), first);
    EXPECT_TRUE(culler.reused());
    // Any change of the spheres or the scale recomputes.
    EXPECT_EQ(culler.unoccluded(ps, fixedRadii(ps, 0.5)),
              unoccludedParticles(ps, fixedRadii(ps, 0.5)));
    EXPECT_FALSE(culler.reused());
    ps.position[62].x += 0.5f;  // the centre particle moves
    EXPECT_EQ(culler.unoccluded(ps, fixedRadii(ps, 0.5)),
              unoccludedParticles(ps, fixedRadii(ps, 0.5)));
    EXPECT_FALSE(culler.reused());
    ps.h[0] = 2.0f;
    EXPECT_EQ(culler.unoccluded(ps, fixedRadii(ps, 0.5)),
              unoccludedParticles(ps, fixedRadii(ps, 0.5)));
    EXPECT_FALSE(culler.reused());
    EXPECT_EQ(culler.unoccluded(ps, fixedRadii(ps, 0.5)),
              unoccludedParticles(ps, fixedRadii(ps, 0.5)));
    EXPECT_TRUE(culler.reused());
}

}  // namespace
}  // namespace twinrender::realtime
