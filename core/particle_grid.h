// Neighbour grids over a particle set, for sums over the particles whose support (radius
// 2 h, sph_kernel.h) covers a point: one uniform grid per octave of h (cells of the octave's
// largest h), so that sets whose smoothing lengths span orders of magnitude still cost
// O(neighbours) per query. Queries visit the particles in a fixed order, so sums over them do
// not depend on the thread count.
//
// Bounded whatever the positions and smoothing lengths: a grid has at most
// max(4 n, 4096) cells. An octave whose box is too sparse for that (a particle far from the
// rest, bodies far apart) is split at its widest empty gap into clusters with a grid each, up
// to MAX_CLUSTER_DEPTH times; a cluster that still does not fit gets coarser cells.
// Non-finite positions and smoothing lengths (which the readers reject) do not widen a grid:
// such particles sit in the first cell.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "core/particles.h"
#include "core/sph_kernel.h"

namespace twinrender::core {

// floor(x) as an integer, clamped to [-2^62, 2^62] (NaN: -2^62), so that any point, however
// far or invalid, gives a cell coordinate that the clamps below handle (std::floor is a
// library call without SSE4.1).
inline std::int64_t floorToInt(double x) {
    constexpr double LIMIT = 4611686018427387904.0;  // 2^62
    if (!(x > -LIMIT)) return -static_cast<std::int64_t>(LIMIT);
    if (x >= LIMIT) return static_cast<std::int64_t>(LIMIT);
    const auto i = static_cast<std::int64_t>(x);
    return static_cast<double>(i) > x ? i - 1 : i;
}

class ParticleGrid {
  public:
    // LANES - 1 padding entries follow the last particle of each level (copies of a real
    // position, coef 0), so that vector loops of LANES may read past the end of the last row.
    static constexpr std::uint32_t LANES = 4;
    // An octave is split into at most 2^MAX_CLUSTER_DEPTH clusters: queries test each
    // cluster's box, so the split ends before that test costs more than a query's sums.
    static constexpr int MAX_CLUSTER_DEPTH = 6;

    // The particles of one octave of h (or of one cluster of it), sorted by cell (ascending
    // index within a cell).
    struct Level {
        double hMax = 0.0;
        double cell = 0.0;
        double invCell = 0.0;
        glm::dvec3 origin{0.0};
        std::int64_t nx = 1, ny = 1, nz = 1;
        std::vector<std::uint32_t> cellStart;  // nx*ny*nz + 1 offsets into the arrays below
        std::vector<float> px, py, pz;         // position
        std::vector<float> invH;               // 1 / h
        std::vector<float> coef;               // v / (pi h^4): dW/dr = coef * w'(r / h)
        std::vector<std::uint32_t> index;      // the particle's index in the set

        std::int64_t cellIndex(std::int64_t ix, std::int64_t iy, std::int64_t iz) const {
            return (iz * ny + iy) * nx + ix;
        }
        std::int64_t coord(double p, double o, std::int64_t n) const {
            return std::clamp<std::int64_t>(floorToInt((p - o) * invCell), 0, n - 1);
        }
    };

    explicit ParticleGrid(const ParticleSet& set);

    const std::vector<Level>& levels() const { return mLevels; }

    // Calls visit(level, begin, end) for the runs [begin, end) of particles of every level
    // whose cells the support sphere around p may reach, in a fixed order (levels, then z, y
    // rows of cells, then particles in grid order). Runs may hold particles beyond the
    // support: the caller tests the distance.
    template <typename Visit>
    void visitSupport(const glm::dvec3& p, Visit&& visit) const {
        for (const Level& g : mLevels) visitLevel(g, p, M4_SUPPORT * g.hMax, visit);
    }

    // The same for the particles within `radius` of p (a neighbourhood of its own size, not
    // the particles' supports): runs in the same fixed order, which may hold particles beyond
    // the radius.
    template <typename Visit>
    void visitBall(const glm::dvec3& p, double radius, Visit&& visit) const {
        for (const Level& g : mLevels) visitLevel(g, p, radius, visit);
    }

  private:
    // Adds the grids of one octave's particles (ascending indices): one, or one per cluster.
    void addClusters(const ParticleSet& set, const std::vector<std::uint32_t>& members, int depth);

    // The runs of level g's cells that the ball of radius `reach` around p reaches.
    template <typename Visit>
    static void visitLevel(const Level& g, const glm::dvec3& p, double reach, Visit& visit);

    std::vector<Level> mLevels;
};

template <typename Visit>
void ParticleGrid::visitLevel(const Level& g, const glm::dvec3& p, double reach, Visit& visit) {
    const double reach2 = reach * reach;
    const std::int64_t rawZ0 = floorToInt((p.z - reach - g.origin.z) * g.invCell);
    const std::int64_t rawZ1 = floorToInt((p.z + reach - g.origin.z) * g.invCell);
    const std::int64_t rawY0 = floorToInt((p.y - reach - g.origin.y) * g.invCell);
    const std::int64_t rawY1 = floorToInt((p.y + reach - g.origin.y) * g.invCell);
    if (rawZ1 < 0 || rawZ0 >= g.nz || rawY1 < 0 || rawY0 >= g.ny) return;
    const std::int64_t z0 = std::max<std::int64_t>(rawZ0, 0), z1 = std::min(rawZ1, g.nz - 1);
    const std::int64_t y0 = std::max<std::int64_t>(rawY0, 0), y1 = std::min(rawY1, g.ny - 1);
    for (std::int64_t iz = z0; iz <= z1; ++iz) {
        const double zLo = g.origin.z + static_cast<double>(iz) * g.cell;
        const double dz = std::max({0.0, zLo - p.z, p.z - (zLo + g.cell)});
        for (std::int64_t iy = y0; iy <= y1; ++iy) {
            const double yLo = g.origin.y + static_cast<double>(iy) * g.cell;
            const double dy = std::max({0.0, yLo - p.y, p.y - (yLo + g.cell)});
            const double rest = reach2 - dy * dy - dz * dz;
            if (rest < 0.0) continue;
            // The row's cells that the ball reaches.
            const double half = std::sqrt(rest);
            const std::int64_t rawX0 = floorToInt((p.x - half - g.origin.x) * g.invCell);
            const std::int64_t rawX1 = floorToInt((p.x + half - g.origin.x) * g.invCell);
            if (rawX1 < 0 || rawX0 >= g.nx) continue;
            const std::int64_t x0 = std::max<std::int64_t>(rawX0, 0);
            const std::int64_t x1 = std::min(rawX1, g.nx - 1);
            const auto first = static_cast<std::size_t>(g.cellIndex(x0, iy, iz));
            const auto last = static_cast<std::size_t>(g.cellIndex(x1, iy, iz));
            visit(g, g.cellStart[first], g.cellStart[last + 1]);
        }
    }
}

}  // namespace twinrender::core
