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
#include "core/particle_grid.h"
#include "core/sph_kernel.h"

namespace twinrender::core {

namespace {

constexpr std::size_t GRAIN = 1024;                   // particles per task
constexpr std::uint32_t LANES = ParticleGrid::LANES;  // partial sums of the gradient loop

// u in [0, 1) after the cast to float (1 - 1e-9 rounds to 1.0f: that is the seam, u = 0).
float wrapU(double u) {
    u -= std::floor(u);
    const auto f = static_cast<float>(u);
    return f >= 1.0f ? 0.0f : f;
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
void accumulateRange(const ParticleGrid::Level& g, std::uint32_t begin, std::uint32_t end,
                     const glm::vec3& q, Lanes& acc) {
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

// grad c(x) at q, in a fixed order (visitSupport's, in LANES partial sums).
FieldSample colourFieldGradient(const ParticleGrid& grids, const glm::vec3& q) {
    Lanes acc;
    grids.visitSupport(glm::dvec3(q),
                       [&](const ParticleGrid::Level& g, std::uint32_t begin, std::uint32_t end) {
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
    double u = std::atan2(p.y, p.x) / (2.0 * std::numbers::pi);
    if (u < 0.0) u += 1.0;
    if (u >= 1.0) u = 0.0;
    out.uv = glm::dvec2(u, std::atan2(p.z, rho) / std::numbers::pi + 0.5);
    if (r2 == 0.0 || rho <= 1e-9 * std::sqrt(r2)) return out;  // on the pole axis
    const glm::dvec3 du(-p.y / (2.0 * std::numbers::pi * rho2),
                        p.x / (2.0 * std::numbers::pi * rho2), 0.0);
    const glm::dvec3 dv(-p.z * p.x / rho, -p.z * p.y / rho, rho);
    out.dudx = frame * du;
    out.dvdx = frame * (dv / (std::numbers::pi * r2));
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
    const ParticleGrid grids(set);
    // Particles are visited in grid order, so that neighbouring queries touch the same cells
    // (random sets are 3-4x slower in index order); each particle's sum does not depend on
    // the visiting order.
    for (const ParticleGrid::Level& level : grids.levels()) {
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

}  // namespace twinrender::core
