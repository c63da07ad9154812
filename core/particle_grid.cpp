#include "core/particle_grid.h"

#include <cmath>
#include <glm/common.hpp>
#include <numbers>

namespace twinrender::core {

namespace {

constexpr double PI = std::numbers::pi;

ParticleGrid::Level buildLevel(const ParticleSet& set, const std::vector<std::uint32_t>& members) {
    ParticleGrid::Level g;
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (std::uint32_t i : members) {
        const glm::dvec3 p(set.position[i]);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
        g.hMax = std::max(g.hMax, static_cast<double>(set.h[i]));
    }
    g.origin = lo;
    const glm::dvec3 extent = hi - lo;
    // Cells of h (half the support): a query visits 5 cells per axis, clipped to the sphere
    // row by row. Coarser where the box is sparse (bodies far apart), so that the dense grid
    // never has more than about 4 cells per particle.
    const double maxCells = std::max(4.0 * static_cast<double>(members.size()), 4096.0);
    g.cell = g.hMax;
    for (;;) {
        const glm::dvec3 n = glm::floor(extent / g.cell) + 1.0;
        const double total = n.x * n.y * n.z;
        if (total <= maxCells) {
            g.nx = static_cast<std::int64_t>(n.x);
            g.ny = static_cast<std::int64_t>(n.y);
            g.nz = static_cast<std::int64_t>(n.z);
            break;
        }
        g.cell *= std::max(1.01, std::cbrt(total / maxCells));
    }

    g.invCell = 1.0 / g.cell;
    const std::size_t cells = static_cast<std::size_t>(g.nx * g.ny * g.nz);
    std::vector<std::uint32_t> cellOf(members.size());
    g.cellStart.assign(cells + 1, 0);
    for (std::size_t m = 0; m < members.size(); ++m) {
        const glm::dvec3 p(set.position[members[m]]);
        const auto c = g.cellIndex(g.coord(p.x, g.origin.x, g.nx), g.coord(p.y, g.origin.y, g.ny),
                                   g.coord(p.z, g.origin.z, g.nz));
        cellOf[m] = static_cast<std::uint32_t>(c);
        ++g.cellStart[static_cast<std::size_t>(c) + 1];
    }
    for (std::size_t c = 0; c < cells; ++c) g.cellStart[c + 1] += g.cellStart[c];
    // Stable counting sort: members are in ascending index order, and stay so within a cell.
    std::vector<std::uint32_t> fill(g.cellStart.begin(), g.cellStart.end() - 1);
    // ParticleGrid::LANES - 1 padding entries (copies of a real position, coef 0) so that the
    // vector loop may read past the end of the last row.
    for (auto* v : {&g.px, &g.py, &g.pz, &g.invH, &g.coef})
        v->resize(members.size() + ParticleGrid::LANES - 1);
    g.index.resize(members.size());
    for (std::size_t m = 0; m < members.size(); ++m) {
        const std::uint32_t i = members[m];
        const glm::vec3& p = set.position[i];
        const double h = set.h[i];
        const std::uint32_t k = fill[cellOf[m]]++;
        g.px[k] = p.x;
        g.py[k] = p.y;
        g.pz[k] = p.z;
        g.invH[k] = static_cast<float>(1.0 / h);
        g.coef[k] = static_cast<float>(set.volume[i] / (PI * h * h * h * h));
        g.index[k] = i;
    }
    for (std::size_t k = members.size(); k < g.px.size(); ++k) {
        g.px[k] = g.px[0];
        g.py[k] = g.py[0];
        g.pz[k] = g.pz[0];
        g.invH[k] = g.invH[0];
        g.coef[k] = 0.0f;
    }
    return g;
}

}  // namespace

// One grid per octave of h: particle i goes to level floor(log2(h_i / h_min)).
ParticleGrid::ParticleGrid(const ParticleSet& set) {
    const std::size_t n = set.size();
    float hMin = INFINITY;
    for (std::size_t i = 0; i < n; ++i) hMin = std::min(hMin, set.h[i]);
    std::vector<std::vector<std::uint32_t>> members;
    for (std::size_t i = 0; i < n; ++i) {
        int e = 0;
        std::frexp(static_cast<double>(set.h[i]) / hMin, &e);  // ratio in [2^(e-1), 2^e)
        const auto level = static_cast<std::size_t>(std::clamp(e - 1, 0, 63));
        if (members.size() <= level) members.resize(level + 1);
        members[level].push_back(static_cast<std::uint32_t>(i));
    }
    for (const auto& m : members)
        if (!m.empty()) mLevels.push_back(buildLevel(set, m));
}

}  // namespace twinrender::core
