#include "core/derived_attributes.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <numbers>
#include <stdexcept>

#include "core/blackbody.h"
#include "core/sph_kernel.h"

namespace twinrender::core {

namespace {

constexpr double PI = std::numbers::pi;
constexpr std::size_t GRAIN = 1024;  // particles per task
constexpr std::uint32_t LANES = 4;   // partial sums of the gradient loop (one SSE vector)

// u in [0, 1) after the cast to float (1 - 1e-9 rounds to 1.0f: that is the seam, u = 0).
float wrapU(double u) {
    u -= std::floor(u);
    const auto f = static_cast<float>(u);
    return f >= 1.0f ? 0.0f : f;
}

// floor(x) as an integer for |x| < 2^62 (std::floor is a library call without SSE4.1).
inline std::int64_t floorToInt(double x) {
    const auto i = static_cast<std::int64_t>(x);
    return static_cast<double>(i) > x ? i - 1 : i;
}

// ---- neighbour grids ---------------------------------------------------------------------

struct GridLevel {
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

GridLevel buildLevel(const ParticleSet& set, const std::vector<std::uint32_t>& members) {
    GridLevel g;
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
    // LANES - 1 padding entries (copies of a real position, coef 0) so that the vector loop
    // may read past the end of the last row.
    for (auto* v : {&g.px, &g.py, &g.pz, &g.invH, &g.coef}) v->resize(members.size() + LANES - 1);
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

// One grid per octave of h: particle i goes to level floor(log2(h_i / h_min)).
std::vector<GridLevel> buildGrids(const ParticleSet& set) {
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
    std::vector<GridLevel> grids;
    for (const auto& m : members)
        if (!m.empty()) grids.push_back(buildLevel(set, m));
    return grids;
}

struct FieldSample {
    glm::dvec3 gradient{0.0};   // grad c at the particle
    double magnitudeSum = 0.0;  // sum_j v_j |dW/dr|: the size the gradient would have if
                                // nothing cancelled
};

// 1 / sqrt(x) for normal positive floats, to float precision (relative error < 1e-6): the
// bit-level first guess (Lomont 2003) and three Newton steps. Plain arithmetic, unlike
// std::sqrt (which may set errno), so that the loop below vectorises without special flags.
inline float reciprocalSqrt(float x) {
    float y = std::bit_cast<float>(0x5F375A86u - (std::bit_cast<std::uint32_t>(x) >> 1));
    const float half = 0.5f * x;
    y = y * (1.5f - half * y * y);
    y = y * (1.5f - half * y * y);
    y = y * (1.5f - half * y * y);
    return y;
}

// Partial sums of the gradient, one per lane, reduced once per particle in a fixed order.
struct Lanes {
    float gx[LANES] = {}, gy[LANES] = {}, gz[LANES] = {}, sum[LANES] = {};
};

// Adds the terms of particles [begin, end) of g to the gradient at q, LANES at a time.
// Branch-free float arithmetic that the compiler turns into SIMD: about two thirds of the
// candidates lie outside the support, and a branch per candidate costs more than computing
// its (zero) term. Beyond the support (s >= 2) the M4 expression is exactly 0, and so is the
// particle's own term (d = 0); lanes past `end` are multiplied by 0.
void accumulateRange(const GridLevel& g, std::uint32_t begin, std::uint32_t end, const glm::vec3& q,
                     Lanes& acc) {
    for (std::uint32_t j = begin; j < end; j += LANES) {
        for (std::uint32_t l = 0; l < LANES; ++l) {
            const std::uint32_t k = j + l;
            const float live = k < end ? 1.0f : 0.0f;
            const float dx = q.x - g.px[k], dy = q.y - g.py[k], dz = q.z - g.pz[k];
            // + FLT_MIN: only changes r2 = 0 (the particle itself) and denormals.
            const float r2 = dx * dx + dy * dy + dz * dz + FLT_MIN;
            const float invR = reciprocalSqrt(r2);
            const float s = r2 * invR * g.invH[k];
            const float dWdr = live * g.coef[k] * m4ShapeDerivativeBranchFree(s);
            const float f = dWdr * invR;
            acc.gx[l] += f * dx;
            acc.gy[l] += f * dy;
            acc.gz[l] += f * dz;
            acc.sum[l] -= dWdr;  // dW/dr <= 0
        }
    }
}

// Calls visit(level, begin, end) for the runs of particles of every grid level whose cells the
// support sphere around p may reach, in a fixed order (levels, then z, y rows of cells, then
// particles in grid order).
template <typename Visit>
void visitSupport(const std::vector<GridLevel>& grids, const glm::dvec3& p, Visit&& visit) {
    for (const GridLevel& g : grids) {
        const double reach = M4_SUPPORT * g.hMax;
        const double reach2 = reach * reach;
        const std::int64_t rawZ0 = floorToInt((p.z - reach - g.origin.z) * g.invCell);
        const std::int64_t rawZ1 = floorToInt((p.z + reach - g.origin.z) * g.invCell);
        const std::int64_t rawY0 = floorToInt((p.y - reach - g.origin.y) * g.invCell);
        const std::int64_t rawY1 = floorToInt((p.y + reach - g.origin.y) * g.invCell);
        if (rawZ1 < 0 || rawZ0 >= g.nz || rawY1 < 0 || rawY0 >= g.ny) continue;
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
                // The row's cells that the support sphere reaches.
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
}

// grad c(x) at q, in a fixed order (visitSupport's, in LANES partial sums).
FieldSample colourFieldGradient(const std::vector<GridLevel>& grids, const glm::vec3& q) {
    Lanes acc;
    visitSupport(grids, glm::dvec3(q),
                 [&](const GridLevel& g, std::uint32_t begin, std::uint32_t end) {
                     accumulateRange(g, begin, end, q, acc);
                 });
    FieldSample out;
    for (std::uint32_t l = 0; l < LANES; ++l) {
        out.gradient += glm::dvec3(acc.gx[l], acc.gy[l], acc.gz[l]);
        out.magnitudeSum += acc.sum[l];
    }
    return out;
}

}  // namespace

SphericalUv sphericalUv(const glm::dvec3& position, const glm::dvec3& center,
                        const glm::dmat3& frame) {
    const glm::dvec3 p = glm::transpose(frame) * (position - center);
    const double rho2 = p.x * p.x + p.y * p.y;
    const double rho = std::sqrt(rho2);
    const double r2 = rho2 + p.z * p.z;
    SphericalUv out;
    double u = std::atan2(p.y, p.x) / (2.0 * PI);
    if (u < 0.0) u += 1.0;
    if (u >= 1.0) u = 0.0;
    out.uv = glm::dvec2(u, std::atan2(p.z, rho) / PI + 0.5);
    if (r2 == 0.0 || rho <= 1e-9 * std::sqrt(r2)) return out;  // on the pole axis
    const glm::dvec3 du(-p.y / (2.0 * PI * rho2), p.x / (2.0 * PI * rho2), 0.0);
    const glm::dvec3 dv(-p.z * p.x / rho, -p.z * p.y / rho, rho);
    out.dudx = frame * du;
    out.dvdx = frame * (dv / (PI * r2));
    return out;
}

void deriveUv(ParticleSet& set, const BodyInfo& body, bool keepUv) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(body.begin, body.end, GRAIN),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                              const SphericalUv s =
                                  sphericalUv(glm::dvec3(set.position[i]), body.center, body.frame);
                              if (keepUv)
                                  set.uv[i] = glm::vec2(wrapU(set.uv[i].x), set.uv[i].y);
                              else
                                  set.uv[i] = glm::vec2(wrapU(s.uv.x), static_cast<float>(s.uv.y));
                              set.dudx[i] = glm::vec3(s.dudx);
                              set.dvdx[i] = glm::vec3(s.dvdx);
                          }
                      });
}

void deriveNormals(ParticleSet& set, std::span<const BodyInfo> bodies) {
    const std::size_t n = set.size();
    if (n == 0) return;
    const std::vector<GridLevel> grids = buildGrids(set);
    // Particles are visited in grid order, so that neighbouring queries touch the same cells
    // (random sets are 3-4x slower in index order); each particle's sum does not depend on
    // the visiting order.
    for (const GridLevel& level : grids) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, level.index.size(), GRAIN),
                          [&](const tbb::blocked_range<std::size_t>& range) {
                              for (std::size_t k = range.begin(); k != range.end(); ++k) {
                                  const std::size_t i = level.index[k];
                                  const glm::dvec3 p(set.position[i]);
                                  const FieldSample f = colourFieldGradient(grids, set.position[i]);
                                  const double len = glm::length(f.gradient);
                                  glm::dvec3 normal;
                                  // Cancellation below what float positions resolve: relative
                                  // rounding of |x| FLT_EPSILON / 2 in each position makes the
                                  // terms of a perfect lattice interior miss each other by up to ~
                                  // |x| FLT_EPSILON / h of their size.
                                  const double resolvable = NORMAL_FALLBACK_RATIO +
                                                            FLT_EPSILON * glm::length(p) / set.h[i];
                                  if (len > resolvable * f.magnitudeSum && len > 0.0) {
                                      normal = -f.gradient / len;
                                  } else {
                                      const BodyInfo& body = bodies[set.body[i]];
                                      const glm::dvec3 radial = p - body.center;
                                      const double rl = glm::length(radial);
                                      normal = rl > 0.0 ? radial / rl : body.frame[2];
                                  }
                                  set.normal[i] = glm::vec3(normal);
                              }
                          });
    }
}

std::vector<FieldDerivatives> colourFieldDerivatives(const ParticleSet& set,
                                                    std::span<const glm::dvec3> points) {
    std::vector<FieldDerivatives> out(points.size());
    if (set.size() == 0 || points.empty()) return out;
    const std::vector<GridLevel> grids = buildGrids(set);
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, points.size(), 64),
        [&](const tbb::blocked_range<std::size_t>& range) {
            for (std::size_t k = range.begin(); k != range.end(); ++k) {
                const glm::dvec3 p = points[k];
                FieldDerivatives& d = out[k];
                visitSupport(grids, p, [&](const GridLevel& g, std::uint32_t begin,
                                           std::uint32_t end) {
                    for (std::uint32_t j = begin; j < end; ++j) {
                        const glm::dvec3 delta = p - glm::dvec3(g.px[j], g.py[j], g.pz[j]);
                        const double r = glm::length(delta);
                        const double invH = g.invH[j];
                        const double q = r * invH;
                        if (q >= M4_SUPPORT || r == 0.0) continue;
                        // dW/dr = coef w'(q), d2W/dr2 = coef w''(q) / h (coef = v / (pi h^4)).
                        const double dWdr = g.coef[j] * m4ShapeDerivative(q);
                        const double d2Wdr2 = g.coef[j] * invH * m4ShapeSecondDerivative(q);
                        const glm::dvec3 u = delta / r;
                        d.gradient += dWdr * u;
                        // Hessian of W(|x - x_j|): W'' u u^T + (W' / r) (I - u u^T).
                        d.hessian += (d2Wdr2 - dWdr / r) * glm::outerProduct(u, u) +
                                     glm::dmat3(dWdr / r);
                    }
                });
            }
        });
    return out;
}

void deriveGlow(ParticleSet& set) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, set.size(), GRAIN),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          // Bodies are runs of one temperature: evaluate once per run.
                          float lastT = NAN;
                          glm::vec3 lastGlow(0.0f);
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                              const float t = set.temperature[i];
                              if (!(t == lastT)) {
                                  lastT = t;
                                  lastGlow = blackbodyRadiance(t);
                              }
                              set.glow[i] = lastGlow;
                          }
                      });
}

void deriveAttributes(ParticleSet& set, std::span<const BodyInfo> bodies,
                      const std::vector<bool>& keepUv) {
    for (std::size_t b = 0; b < bodies.size(); ++b)
        deriveUv(set, bodies[b], b < keepUv.size() && keepUv[b]);
    deriveNormals(set, bodies);
    deriveGlow(set);
}

}  // namespace twinrender::core
