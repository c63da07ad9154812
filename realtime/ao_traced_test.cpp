#include "realtime/ao_traced.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace twinrender::realtime {
namespace {

// `n` particles scattered in a box of side 2 about (5, -3, 1), the last of them of radius 0.
core::ParticleSet scatteredParticles(int n, std::vector<float>& radii) {
    core::ParticleSet ps;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), r(0.02f, 0.15f);
    for (int i = 0; i < n; ++i) {
        ps.position.emplace_back(5.0f + u(rng), -3.0f + u(rng), 1.0f + u(rng));
        radii.push_back(i == n - 1 ? 0.0f : r(rng));
    }
    return ps;
}

// Whether the sphere's box overlaps the cell (x, y, z) of the grid, with a tolerance of `slack`.
bool boxOverlaps(const OcclusionGrid& g, const glm::vec4& s, glm::ivec3 cell, double slack) {
    for (int a = 0; a < 3; ++a) {
        const double lo = g.origin[a] + g.side * cell[a], hi = lo + g.side;
        if (s[a] + s.w < lo - slack || s[a] - s.w > hi + slack) return false;
    }
    return true;
}

TEST(OcclusionGrid, ListsEachSphereInTheCellsItsBoxOverlapsInParticleOrder) {
    std::vector<float> radii;
    const core::ParticleSet ps = scatteredParticles(300, radii);
    const glm::dvec3 camera(4.0, -2.0, 0.0);
    const OcclusionGrid g = buildOcclusionGrid(ps, radii, {}, camera, 0.5);
    // The radius-0 particle is left out; the others in order, camera-relative.
    ASSERT_EQ(g.spheres.size(), 299u);
    EXPECT_FLOAT_EQ(g.spheres[3].x, ps.position[3].x - 4.0f);
    EXPECT_FLOAT_EQ(g.spheres[3].w, radii[3]);
    // Cells of the largest radius (here above reach / 64).
    EXPECT_FLOAT_EQ(g.side, *std::max_element(radii.begin(), radii.end()));
    const std::size_t cells = static_cast<std::size_t>(g.cells.x) * g.cells.y * g.cells.z;
    ASSERT_EQ(g.cellStart.size(), cells + 1);
    EXPECT_EQ(g.cellStart.back(), g.items.size());
    for (int z = 0; z < g.cells.z; ++z)
        for (int y = 0; y < g.cells.y; ++y)
            for (int x = 0; x < g.cells.x; ++x) {
                const std::size_t c = x + g.cells.x * (y + std::size_t(g.cells.y) * z);
                const std::vector<std::uint32_t> listed(g.items.begin() + g.cellStart[c],
                                                        g.items.begin() + g.cellStart[c + 1]);
                EXPECT_TRUE(std::is_sorted(listed.begin(), listed.end()));
                // Every sphere whose box overlaps the cell is listed; every listed one's box
                // reaches it (within the build's padding).
                for (std::uint32_t k = 0; k < g.spheres.size(); ++k) {
                    const bool isListed = std::binary_search(listed.begin(), listed.end(), k);
                    if (boxOverlaps(g, g.spheres[k], {x, y, z}, -1e-4 * g.side)) {
                        EXPECT_TRUE(isListed) << k << " in " << c;
                    }
                    if (isListed) {
                        EXPECT_TRUE(boxOverlaps(g, g.spheres[k], {x, y, z}, 1e-4 * g.side));
                    }
                }
            }
    // The same grid again: the build is deterministic.
    const OcclusionGrid again = buildOcclusionGrid(ps, radii, {}, camera, 0.5);
    EXPECT_EQ(again.items, g.items);
    EXPECT_EQ(again.cellStart, g.cellStart);
}

TEST(OcclusionGrid, TakesOnlyTheIndicesGivenAndCapsItsCells) {
    std::vector<float> radii;
    const core::ParticleSet ps = scatteredParticles(50, radii);
    const std::vector<std::uint32_t> some = {2, 10, 49};  // 49 has radius 0
    const OcclusionGrid g = buildOcclusionGrid(ps, radii, some, glm::dvec3(0.0), 0.5);
    ASSERT_EQ(g.spheres.size(), 2u);
    EXPECT_FLOAT_EQ(g.spheres[1].y, ps.position[10].y);
    // Two small spheres far apart: cells of their radius would be thousands; the grid keeps
    // at most max(8 per sphere, 4096).
    std::vector<float> tiny = {0.001f, 0.001f};
    core::ParticleSet far;
    far.position = {glm::vec3(0.0f), glm::vec3(10.0f)};
    const OcclusionGrid capped = buildOcclusionGrid(far, tiny, {}, glm::dvec3(0.0), 0.0);
    EXPECT_LE(std::size_t(capped.cells.x) * capped.cells.y * capped.cells.z, 4096u);
    EXPECT_EQ(capped.items.size(), 2u);
    // No sphere: one empty cell.
    const OcclusionGrid none =
        buildOcclusionGrid(far, std::vector<float>{0.0f, 0.0f}, {}, glm::dvec3(0.0), 1.0);
    EXPECT_TRUE(none.spheres.empty());
    EXPECT_EQ(none.cellStart, (std::vector<std::uint32_t>{0, 0}));
}

}  // namespace
}  // namespace twinrender::realtime
