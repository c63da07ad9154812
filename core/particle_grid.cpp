#include "core/particle_grid.h"

#include <cmath>
#include <glm/common.hpp>
#include <numbers>

namespace twinrender::core {

namespace {

// The box of the finite positions and the largest finite h of some particles of a set.
struct Box {
    glm::dvec3 lo{INFINITY};
    glm::dvec3 hi{-INFINITY};
    double hMax = 0.0;
};

Box boxOf(const ParticleSet& set, const std::vector<std::uint32_t>& members) {
    Box b;
    for (std::uint32_t i : members) {
        const glm::dvec3 p(set.position[i]);
        if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
            b.lo = glm::min(b.lo, p);
            b.hi = glm::max(b.hi, p);
        }
        const double h = set.h[i];
        if (std::isfinite(h)) b.hMax = std::max(b.hMax, h);
    }
    if (!(b.lo.x <= b.hi.x)) b.lo = b.hi = glm::dvec3(0.0);  // no finite position
    return b;
}

// A dense grid never has more than about 4 cells per particle.
double maxCells(std::size_t particles) {
    return std::max(4.0 * static_cast<double>(particles), 4096.0);
}

// Whether a grid of cells of size `cell` over `extent` has at most `most` cells.
bool fits(const glm::dvec3& extent, double cell, double most) {
    const glm::dvec3 n = glm::floor(extent / cell) + 1.0;
    return n.x * n.y * n.z <= most;
}

// Cells of h (half the support): a query visits 5 cells per axis, clipped to the sphere row
// by row. Coarser where the box is sparse, so that the grid has at most `most` cells.
double cellSize(const glm::dvec3& extent, double h, double most) {
    const double span = std::max({extent.x, extent.y, extent.z, 0.0});
    double cell = h;
    if (!(cell > 0.0)) cell = span > 0.0 ? span : 1.0;  // h = 0 everywhere: one cell per span
    // Each step takes at least a third off log(count / most) (at least 1 % off the count once
    // the ratio is small): about 20 steps from the most extreme float set (h 1e-45, extent
    // 7e38, count 1e250); the bound only keeps a non-finite extent from looping.
    for (int step = 0; step < 1000 && !fits(extent, cell, most); ++step) {
        const glm::dvec3 n = glm::floor(extent / cell) + 1.0;
        cell *= std::max(1.01, std::cbrt(n.x * n.y * n.z / most));
    }
    // At most 2 cells per axis.
    if (!fits(extent, cell, most)) cell = span;
    return cell;
}

ParticleGrid::Level buildLevel(const ParticleSet& set, const std::vector<std::uint32_t>& members,
                               const Box& box) {
    ParticleGrid::Level g;
    g.hMax = box.hMax;
    g.origin = box.lo;
    const glm::dvec3 extent = box.hi - box.lo;
    g.cell = cellSize(extent, g.hMax, maxCells(members.size()));
    const glm::dvec3 n = glm::floor(extent / g.cell) + 1.0;
    g.nx = static_cast<std::int64_t>(n.x);
    g.ny = static_cast<std::int64_t>(n.y);
    g.nz = static_cast<std::int64_t>(n.z);

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
        g.coef[k] = static_cast<float>(set.volume[i] / (std::numbers::pi * h * h * h * h));
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

// Where to split a sparse cluster: the widest gap between the particles' coordinates along
// an axis; particles at or below `at` form one side. None when no gap is wider than the
// support's diameter (4 h), across which no query reaches from one side to the other.
struct Split {
    int axis = -1;
    double at = 0.0;
};

Split widestGap(const ParticleSet& set, const std::vector<std::uint32_t>& members, double hMax) {
    Split best;
    double widest = 2.0 * M4_SUPPORT * hMax;
    std::vector<float> c;
    c.reserve(members.size());
    for (int axis = 0; axis < 3; ++axis) {
        c.clear();
        for (std::uint32_t i : members)
            if (std::isfinite(set.position[i][axis])) c.push_back(set.position[i][axis]);
        std::sort(c.begin(), c.end());
        for (std::size_t k = 1; k < c.size(); ++k) {
            const double gap = static_cast<double>(c[k]) - static_cast<double>(c[k - 1]);
            if (gap > widest) {
                widest = gap;
                best = {axis, c[k - 1]};
            }
        }
    }
    return best;
}

}  // namespace

void ParticleGrid::addClusters(const ParticleSet& set, const std::vector<std::uint32_t>& members,
                               int depth) {
    const Box box = boxOf(set, members);
    if (depth < MAX_CLUSTER_DEPTH && !fits(box.hi - box.lo, box.hMax, maxCells(members.size()))) {
        const Split split = widestGap(set, members, box.hMax);
        if (split.axis >= 0) {
            // Both sides keep ascending index order, which buildLevel's sort relies on.
            std::vector<std::uint32_t> low, high;
            for (std::uint32_t i : members)
                (set.position[i][split.axis] > split.at ? high : low).push_back(i);
            addClusters(set, low, depth + 1);
            addClusters(set, high, depth + 1);
            return;
        }
    }
    mLevels.push_back(buildLevel(set, members, box));
}

// One grid per octave of h: particle i goes to level floor(log2(h_i / h_min)). A non-finite
// or non-positive h (which the readers reject) goes to the first.
ParticleGrid::ParticleGrid(const ParticleSet& set) {
    const std::size_t n = set.size();
    float hMin = INFINITY;
    for (std::size_t i = 0; i < n; ++i)
        if (set.h[i] > 0.0f) hMin = std::min(hMin, set.h[i]);
    std::vector<std::vector<std::uint32_t>> members;
    for (std::size_t i = 0; i < n; ++i) {
        int e = 0;
        const double ratio = static_cast<double>(set.h[i]) / hMin;
        if (std::isfinite(ratio)) std::frexp(ratio, &e);  // ratio in [2^(e-1), 2^e)
        const auto level = static_cast<std::size_t>(std::clamp(e - 1, 0, 63));
        if (members.size() <= level) members.resize(level + 1);
        members[level].push_back(static_cast<std::uint32_t>(i));
    }
    for (const auto& m : members)
        if (!m.empty()) addClusters(set, m, 0);
}

}  // namespace twinrender::core
