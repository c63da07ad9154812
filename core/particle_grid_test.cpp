#include "core/particle_grid.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "core/colour_field.h"
#include "core/derived_attributes.h"
#include "core/particle_generators.h"
#include "core/sph_kernel.h"

namespace twinrender::core {
namespace {

// n particles in the unit cube (a random set), h = 0.1, volumes at the cap.
ParticleSet cube(std::size_t n, std::uint64_t seed = 3) {
    SplitMix64 rng(seed);
    ParticleSet set;
    set.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        set.position[i] = glm::vec3(glm::dvec3(rng.uniform(), rng.uniform(), rng.uniform()));
        set.h[i] = 0.1f;
        set.volume[i] = static_cast<float>(maxParticleVolume(0.1));
    }
    return set;
}

// What bounds the work of a grid: every particle in exactly one level, and no level with more
// than max(4 n, 4096) cells (n: the set's size, an upper bound of the level's).
void expectBounded(const ParticleGrid& grid, std::size_t n) {
    std::size_t particles = 0;
    for (const ParticleGrid::Level& g : grid.levels()) {
        const double cells = static_cast<double>(g.nx) * g.ny * g.nz;
        EXPECT_GE(g.nx, 1);
        EXPECT_GE(g.ny, 1);
        EXPECT_GE(g.nz, 1);
        EXPECT_LE(cells, std::max(4.0 * n, 4096.0));
        EXPECT_EQ(g.cellStart.size(), static_cast<std::size_t>(cells) + 1);
        EXPECT_EQ(g.cellStart.back(), g.index.size());
        particles += g.index.size();
    }
    EXPECT_EQ(particles, n);
}

// The particles visitBall finds within `radius` of p, by index.
std::vector<std::uint32_t> ballMembers(const ParticleGrid& grid, const glm::dvec3& p,
                                       double radius) {
    std::vector<std::uint32_t> found;
    grid.visitBall(p, radius,
                   [&](const ParticleGrid::Level& g, std::uint32_t begin, std::uint32_t end) {
                       for (std::uint32_t k = begin; k < end; ++k) {
                           const glm::dvec3 d = glm::dvec3(g.px[k], g.py[k], g.pz[k]) - p;
                           if (glm::dot(d, d) <= radius * radius) found.push_back(g.index[k]);
                       }
                   });
    std::sort(found.begin(), found.end());
    return found;
}

std::vector<std::uint32_t> bruteBall(const ParticleSet& set, const glm::dvec3& p, double radius) {
    std::vector<std::uint32_t> found;
    for (std::uint32_t i = 0; i < set.size(); ++i) {
        const glm::dvec3 d = glm::dvec3(set.position[i]) - p;
        if (glm::dot(d, d) <= radius * radius) found.push_back(i);
    }
    return found;
}

// One particle 1e30 away from a body: the body keeps cells of h (its queries stay
// O(neighbours)), in a cluster of its own, and queries find what a brute-force search finds.
TEST(ParticleGrid, ParticleFarFromTheRestGetsAClusterOfItsOwn) {
    ParticleSet set = cube(3000);
    set.position[1234] = glm::vec3(1e30f, -2e29f, 5e29f);
    const ParticleGrid grid(set);
    expectBounded(grid, set.size());
    ASSERT_EQ(grid.levels().size(), 2u);
    std::size_t bulk = 0;
    for (const auto& g : grid.levels())
        if (g.index.size() > 1) {
            ++bulk;
            EXPECT_FLOAT_EQ(g.cell, 0.1) << "the body's cells were coarsened";
        }
    EXPECT_EQ(bulk, 1u);
    for (const glm::dvec3 p : {glm::dvec3(0.5), glm::dvec3(1e30, -2e29, 5e29), glm::dvec3(-3.0)})
        EXPECT_EQ(ballMembers(grid, p, 0.2), bruteBall(set, p, 0.2));
}

// Coincident, sparse and degenerate sets: grids stay within their cell bound and queries
// still find every particle a brute-force search finds.
TEST(ParticleGrid, BoundedForExtremePositionsAndSmoothingLengths) {
    struct Case {
        const char* name;
        std::function<void(ParticleSet&)> edit;
    };
    const Case cases[] = {
        {"h denormal", [](ParticleSet& s) { std::fill(s.h.begin(), s.h.end(), 1e-40f); }},
        {"h zero", [](ParticleSet& s) { std::fill(s.h.begin(), s.h.end(), 0.0f); }},
        {"h 1e30", [](ParticleSet& s) { std::fill(s.h.begin(), s.h.end(), 1e30f); }},
        {"h spans 1e-38..1e38",
         [](ParticleSet& s) {
             for (std::size_t i = 0; i < s.size(); ++i) s.h[i] = i % 2 ? 1e-38f : 1e38f;
         }},
        {"positions at the float range",
         [](ParticleSet& s) {
             for (std::size_t i = 0; i < s.size(); ++i)
                 s.position[i] *= i % 3 == 0 ? FLT_MAX : (i % 3 == 1 ? -FLT_MAX : 1.0f);
         }},
        {"denormal positions",
         [](ParticleSet& s) {
             for (auto& p : s.position) p *= 1e-39f;
         }},
        {"all coincident",
         [](ParticleSet& s) { std::fill(s.position.begin(), s.position.end(), glm::vec3(2.0f)); }},
        {"NaN and infinite positions and h",
         [](ParticleSet& s) {
             s.position[1] = glm::vec3(NAN, 0.0f, 0.0f);
             s.position[2] = glm::vec3(0.0f, INFINITY, 0.0f);
             s.h[3] = NAN;
             s.h[4] = INFINITY;
             s.h[5] = -1.0f;
         }},
        {"sparse cloud",
         [](ParticleSet& s) {
             for (std::size_t i = 0; i < s.size(); ++i) s.position[i] *= std::pow(10.0f, i % 30);
         }},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        ParticleSet set = cube(2000);
        c.edit(set);
        const ParticleGrid grid(set);
        expectBounded(grid, set.size());
        for (const glm::dvec3 p : {glm::dvec3(0.5), glm::dvec3(2.0), glm::dvec3(NAN),
                                   glm::dvec3(1e300), glm::dvec3(-INFINITY)}) {
            std::vector<std::uint32_t> expected = bruteBall(set, p, 0.3);
            // A non-finite particle is never within a distance of anything.
            EXPECT_EQ(ballMembers(grid, p, 0.3), expected) << p.x;
        }
    }
}

// The normals of a body are those of the body alone when one particle is added far away:
// the body's grid is the same (the same box, cells and order), so the sums are bit-identical.
TEST(ParticleGrid, FarParticleLeavesTheNormalsOfTheRest) {
    const std::size_t n = 1500;
    ParticleSet alone = cube(n, 9);
    ParticleSet with = alone;
    with.resize(n + 1);
    with.position[n] = glm::vec3(-3e37f, 0.0f, 0.0f);
    with.h[n] = 0.1f;
    with.volume[n] = alone.volume[0];
    BodyInfo body;
    body.end = n;
    deriveNormals(alone, std::span<const BodyInfo>(&body, 1));
    body.end = n + 1;
    deriveNormals(with, std::span<const BodyInfo>(&body, 1));
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(alone.normal[i], with.normal[i]) << i;
    EXPECT_TRUE(std::isfinite(with.normal[n].x));
}

}  // namespace
}  // namespace twinrender::core
