#include "realtime/occlusion_culling.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <map>
#include <unordered_map>

namespace twinrender::realtime {

namespace {

using DirectionGrid = CullingDirections;

DirectionGrid makeDirectionGrid() {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<glm::dvec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                 {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                 {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (auto& p : v) p = glm::normalize(p);
    std::vector<std::array<int, 3>> faces = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    // The largest angular circumradius of the triangles, rounded up.
    auto coveringAngle = [&] {
        double largest = 0.0;
        for (const auto& f : faces) {
            // The circumcentre of a spherical triangle is the normalised normal of its plane.
            glm::dvec3 centre = glm::normalize(glm::cross(v[f[1]] - v[f[0]], v[f[2]] - v[f[0]]));
            if (glm::dot(centre, v[f[0]]) < 0.0) centre = -centre;
            largest =
                std::max(largest, std::acos(std::clamp(glm::dot(centre, v[f[0]]), -1.0, 1.0)));
        }
        return largest * (1.0 + 1e-6);  // rounding margin
    };
    DirectionGrid grid;
    for (int level = 0; level < 2; ++level) {
        if (level == 1) {
            grid.coarseCount = v.size();
            grid.coarseCoveringAngle = coveringAngle();
        }
        std::map<std::pair<int, int>, int> midpoints;
        auto midpoint = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            auto it = midpoints.find(key);
            if (it != midpoints.end()) return it->second;
            v.push_back(glm::normalize(v[a] + v[b]));
            return midpoints[key] = static_cast<int>(v.size()) - 1;
        };
        std::vector<std::array<int, 3>> next;
        for (const auto& f : faces) {
            const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
            next.push_back({f[0], a, c});
            next.push_back({f[1], b, a});
            next.push_back({f[2], c, b});
            next.push_back({a, b, c});
        }
        faces = std::move(next);
    }
    grid.directions = v;
    grid.coveringAngle = coveringAngle();
    return grid;
}

// Neighbours within this many radii are tested over all directions first (hcp's nearest 12 at
// 0.96 r and cubic's 6 + 12 at 0.85 r and 1.21 r, for impostors of 0.9 h = 1.17 s).
constexpr float NEAR_SHELL = 1.4f;

// Cells of the search grid, keyed by packed integer coordinates (21 bits each).
std::uint64_t cellKey(std::int64_t x, std::int64_t y, std::int64_t z) {
    constexpr std::int64_t OFFSET = 1 << 20;
    auto part = [](std::int64_t v) { return static_cast<std::uint64_t>(v + OFFSET) & 0x1FFFFF; };
    return part(x) | part(y) << 21 | part(z) << 42;
}

// Bodies whose largest impostor exceeds this many times the median are not culled.
constexpr double MAX_RADIUS_RATIO = 8.0;

// Culls within one group of particles (a body): marks visible[i] = 0 for its buried members.
void cullGroup(const core::ParticleSet& ps, const std::vector<std::uint32_t>& members,
               std::span<const float> allRadii, std::vector<unsigned char>& visibleOut) {
    const std::size_t n = members.size();
    if (n < 2) return;

    const DirectionGrid& grid = cullingDirections();
    const double cosMargin = std::cos(grid.coveringAngle), sinMargin = std::sin(grid.coveringAngle);

    std::vector<double> radii(n);
    glm::dvec3 lo(std::numeric_limits<double>::max());
    for (std::size_t k = 0; k < n; ++k) {
        radii[k] = allRadii[members[k]];
        lo = glm::min(lo, glm::dvec3(ps.position[members[k]]));
    }
    // The grid's cells are twice the largest radius, so a few huge spheres would make it
    // quadratic: leave bodies of very uneven h (beyond 8x the median) unculled.
    std::vector<double> sortedRadii = radii;
    std::nth_element(sortedRadii.begin(), sortedRadii.begin() + n / 2, sortedRadii.end());
    const double medianRadius = sortedRadii[n / 2];
    const double maxRadius = *std::max_element(radii.begin(), radii.end());
    if (!(maxRadius > 0.0) || maxRadius > MAX_RADIUS_RATIO * medianRadius) return;
    // Spheres that overlap lie within r_i + r_j <= 2 maxRadius: the 27 cells around a cell of
    // that size hold every candidate.
    const double cellSize = 2.0 * maxRadius;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> sorted(n);  // (cell key, member)
    for (std::size_t k = 0; k < n; ++k) {
        const glm::dvec3 c = (glm::dvec3(ps.position[members[k]]) - lo) / cellSize;
        if (std::max({c.x, c.y, c.z}) >= double(1 << 20)) return;  // too sparse a body
        sorted[k] = {cellKey(static_cast<std::int64_t>(c.x), static_cast<std::int64_t>(c.y),
                             static_cast<std::int64_t>(c.z)),
                     static_cast<std::uint32_t>(k)};
    }
    std::sort(sorted.begin(), sorted.end());
    // Positions relative to the body's corner `lo` (float keeps its precision inside one body)
    // and radii, in cell order; original particle indices for ties.
    std::vector<float> px(n), py(n), pz(n), pr(n);
    std::vector<std::uint32_t> original(n);
    for (std::size_t k = 0; k < n; ++k) {
        const std::uint32_t m = sorted[k].second;
        const glm::dvec3 p = glm::dvec3(ps.position[members[m]]) - lo;
        px[k] = static_cast<float>(p.x);
        py[k] = static_cast<float>(p.y);
        pz[k] = static_cast<float>(p.z);
        pr[k] = static_cast<float>(radii[m]);
        original[k] = members[m];
    }
    struct Range {
        std::size_t begin, end;
    };
    std::vector<Range> cellRanges;
    std::unordered_map<std::uint64_t, std::size_t> cellIndex;
    for (std::size_t k = 0; k < n;) {
        std::size_t e = k;
        while (e < n && sorted[e].first == sorted[k].first) ++e;
        cellIndex.emplace(sorted[k].first, cellRanges.size());
        cellRanges.push_back({k, e});
        k = e;
    }

    // Directions as float columns.
    const std::size_t directionCount = grid.directions.size();
    std::vector<float> dirX(directionCount), dirY(directionCount), dirZ(directionCount);
    for (std::size_t k = 0; k < directionCount; ++k) {
        dirX[k] = static_cast<float>(grid.directions[k].x);
        dirY[k] = static_cast<float>(grid.directions[k].y);
        dirZ[k] = static_cast<float>(grid.directions[k].z);
    }

    // visible[k] for the k-th particle in cell order.
    std::vector<unsigned char> visible(n, 1);
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, cellRanges.size(), 8), [&](const auto& range) {
            struct Cap {
                float x, y, z;
                float minCos;  // a direction d is covered with margin when dot(d, axis) >= minCos
            };
            std::vector<std::size_t> candidates;
            std::vector<float> cx, cy, cz, cr, d2;
            std::vector<std::pair<float, std::size_t>> near, rest;
            std::vector<Cap> caps;
            std::vector<float> margin(directionCount);
            for (std::size_t cell = range.begin(); cell != range.end(); ++cell) {
                const std::uint64_t key = sorted[cellRanges[cell].begin].first;
                const auto coord = [&](int shift) {
                    return static_cast<std::int64_t>((key >> shift) & 0x1FFFFF) - (1 << 20);
                };
                const std::int64_t x = coord(0), y = coord(21), z = coord(42);
                // The candidates of this cell, gathered once into contiguous columns.
                candidates.clear();
                for (std::int64_t dz = -1; dz <= 1; ++dz)
                    for (std::int64_t dy = -1; dy <= 1; ++dy)
                        for (std::int64_t dx = -1; dx <= 1; ++dx) {
                            auto it = cellIndex.find(cellKey(x + dx, y + dy, z + dz));
                            if (it == cellIndex.end()) continue;
                            for (std::size_t k = cellRanges[it->second].begin;
                                 k < cellRanges[it->second].end; ++k)
                                candidates.push_back(k);
                        }
                const std::size_t m = candidates.size();
                cx.resize(m);
                cy.resize(m);
                cz.resize(m);
                cr.resize(m);
                d2.resize(m);
                for (std::size_t c = 0; c < m; ++c) {
                    cx[c] = px[candidates[c]];
                    cy[c] = py[candidates[c]];
                    cz[c] = pz[candidates[c]];
                    cr[c] = pr[candidates[c]];
                }
                for (std::size_t k = cellRanges[cell].begin; k < cellRanges[cell].end; ++k) {
                    const float xi = px[k], yi = py[k], zi = pz[k], ri = pr[k];
                    const std::uint32_t i = original[k];
                    {
                        // Squared distances minus squared reach: negative where spheres overlap.
                        const float* __restrict ax = cx.data();
                        const float* __restrict ay = cy.data();
                        const float* __restrict az = cz.data();
                        const float* __restrict ar = cr.data();
                        float* __restrict out = d2.data();
                        for (std::size_t c = 0; c < m; ++c) {
                            const float dx = ax[c] - xi, dy = ay[c] - yi, dz = az[c] - zi;
                            const float reach = ri + ar[c];
                            out[c] = dx * dx + dy * dy + dz * dz - reach * reach;
                        }
                    }
                    // The overlapping neighbours, nearest first: the nearest bury a sphere, and
                    // testing a subset can only keep a sphere that could have been culled.
                    near.clear();
                    bool hidden = false;
                    for (std::size_t c = 0; c < m; ++c) {
                        if (d2[c] >= 0.0f || candidates[c] == k) continue;
                        const float rj = cr[c];
                        const float dx = cx[c] - xi, dy = cy[c] - yi, dz = cz[c] - zi;
                        const float dist2 = dx * dx + dy * dy + dz * dz;
                        // Sphere i inside sphere j (needs rj >= ri); of two equal coincident
                        // spheres, the lower index stays.
                        if (rj >= ri && std::sqrt(dist2) + ri <= rj) {
                            if (dist2 > 0.0f || rj > ri || original[candidates[c]] < i) {
                                hidden = true;
                                break;
                            }
                            continue;
                        }
                        if (dist2 > 0.0f) near.push_back({dist2, candidates[c]});
                    }
                    if (hidden) {
                        visible[k] = 0;
                        continue;
                    }
                    if (near.empty()) continue;
                    // Sphere j covers the cap of sphere i within angle g of d / |d|:
                    // cos g = (|d|^2 + ri^2 - rj^2) / (2 |d| ri). A direction counts as covered
                    // only with the grid's covering margin: cos(g - margin), without
                    // trigonometric calls, rounded up by far more than the float error of the
                    // axis and the directions, so the test stays conservative.
                    auto makeCap = [&](float dist2, std::size_t c, Cap& cap) {
                        const float rj = pr[c];
                        const float dist = std::sqrt(dist2);
                        const double cosG = std::clamp(
                            (double(dist2) + double(ri) * ri - double(rj) * rj) / (2.0 * dist * ri),
                            -1.0, 1.0);
                        if (cosG >= cosMargin) return false;  // g <= margin: covers nothing
                        const double sinG = std::sqrt(1.0 - cosG * cosG);
                        const float inv = 1.0f / dist;
                        cap = {(px[c] - xi) * inv, (py[c] - yi) * inv, (pz[c] - zi) * inv,
                               static_cast<float>(cosG * cosMargin + sinG * sinMargin + 1e-4)};
                        return true;
                    };
                    // Stage 1: the nearest neighbours (within 1.4 radii: the first shells of
                    // hcp and cubic lattices, whose caps are widest) over every direction, in a
                    // branch-free loop that vectorises; margin[d] >= 0: direction d covered.
                    const float nearLimit2 = NEAR_SHELL * NEAR_SHELL * ri * ri;
                    caps.clear();
                    rest.clear();
                    for (const auto& [dist2, c] : near) {
                        Cap cap;
                        if (dist2 > nearLimit2)
                            rest.push_back({dist2, c});
                        else if (makeCap(dist2, c, cap))
                            caps.push_back(cap);
                    }
                    std::fill(margin.begin(), margin.end(), -1.0f);
                    for (const Cap& cap : caps) {
                        const float ax = cap.x, ay = cap.y, az = cap.z, minCos = cap.minCos;
                        float* __restrict mg = margin.data();
                        const float* __restrict dx = dirX.data();
                        const float* __restrict dy = dirY.data();
                        const float* __restrict dz = dirZ.data();
                        for (std::size_t d = 0; d < directionCount; ++d)
                            mg[d] = std::max(mg[d], dx[d] * ax + dy[d] * ay + dz[d] * az - minCos);
                    }
                    // Stage 2, for directions still open: the farther neighbours.
                    bool built = false;
                    bool covered = true;
                    for (std::size_t d = 0; d < directionCount && covered; ++d) {
                        if (margin[d] >= 0.0f) continue;
                        if (!built) {
                            caps.clear();
                            for (const auto& [dist2, c] : rest) {
                                Cap cap;
                                if (makeCap(dist2, c, cap)) caps.push_back(cap);
                            }
                            built = true;
                        }
                        covered = false;
                        for (const Cap& cap : caps)
                            if (dirX[d] * cap.x + dirY[d] * cap.y + dirZ[d] * cap.z >= cap.minCos) {
                                covered = true;
                                break;
                            }
                    }
                    if (covered) visible[k] = 0;
                }
            }
        });
    for (std::size_t k = 0; k < n; ++k)
        if (!visible[k]) visibleOut[original[k]] = 0;
}

}  // namespace

const CullingDirections& cullingDirections() {
    static const CullingDirections grid = makeDirectionGrid();
    return grid;
}

std::vector<std::uint32_t> unoccludedParticles(const core::ParticleSet& ps,
                                               std::span<const float> radii) {
    // Bodies are culled one by one: each in its own coordinates (so float keeps precision in
    // scenes spanning many orders of magnitude) and with its own grid. Spheres of one body
    // covering another body's are not used, which can only keep more spheres.
    std::map<std::uint32_t, std::vector<std::uint32_t>> bodies;
    for (std::size_t i = 0; i < ps.size(); ++i)
        bodies[ps.body.empty() ? 0u : ps.body[i]].push_back(static_cast<std::uint32_t>(i));
    std::vector<unsigned char> visible(ps.size(), 1);
    for (const auto& [body, members] : bodies) cullGroup(ps, members, radii, visible);
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < ps.size(); ++i)
        if (visible[i]) out.push_back(static_cast<std::uint32_t>(i));
    return out;
}

const std::vector<std::uint32_t>& OcclusionCuller::unoccluded(const core::ParticleSet& ps,
                                                              std::span<const float> radii) {
    return mCache.get(
        ps, [&] { return unoccludedParticles(ps, radii); }, radii);
}

}  // namespace twinrender::realtime
