// Per-particle attributes derived once in core/ and shared by both renderers (docs/design.md, "Data
// flow"): texture coordinates and their gradient, the colour-field normal, the blackbody glow.
// Everything is a pure function of the particle set: parallel over particles (oneTBB), each
// particle computed by one task with a fixed summation order, so the results are bit-identical for
// any thread count.
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "core/colour_field.h"
#include "core/particles.h"

namespace twinrender::core {

// Body-local spherical texture coordinates of a point. With p = frame^T (x - center) =
// (px, py, pz) in the body frame (z = the pole axis), rho = sqrt(px^2 + py^2), r = |p|:
//   u = atan2(py, px) / (2 pi), wrapped to [0, 1)   (longitude; the seam is the local +x half
//                                                     plane, u grows eastward = counter-
//                                                     clockwise about the pole),
//   v = atan2(pz, rho) / pi + 1/2                   (latitude: 0 south pole, 1 north pole),
// and their analytic gradients (1/scene unit, world space):
//   grad u = (-py, px, 0) / (2 pi rho^2),  grad v = (-pz px / rho, -pz py / rho, rho) / (pi r^2)
// rotated back by `frame`. On the pole axis (rho <= 1e-9 r, or r = 0) both gradients are set
// to 0: their direction is undefined there (u is singular, v has a cone point).
struct SphericalUv {
    glm::dvec2 uv{0.0};
    glm::dvec3 dudx{0.0};
    glm::dvec3 dvdx{0.0};
};
SphericalUv sphericalUv(const glm::dvec3& position, const glm::dvec3& center,
                        const glm::dmat3& frame);

// uv, dudx, dvdx of the particles [body.begin, body.end) from sphericalUv around body.center
// with body.frame. keepUv: the uv already in the set (read from a file) is kept (u wrapped to
// [0, 1)), and only the gradients are taken from the spherical mapping: a file gives no
// gradient, and the spherical one has the right scale for texture filtering.
void deriveUv(ParticleSet& particles, const BodyInfo& body, bool keepUv);

// normal = -grad c / |grad c| of the colour field c(x) = sum_j v_j W(|x - x_j|, h_j) (M4
// kernel, sph_kernel.h), over every particle of the set whose support 2 h_j covers x_i, all
// bodies included (it is the field whose level set the raymarcher renders).
// Fallback: where the gradient cancels, |grad c| <= (NORMAL_FALLBACK_RATIO + FLT_EPSILON
// |x_i| / h_i) * sum_j v_j |dW/dr| (interior particles of a lattice, whose neighbours balance
// out), the normal is the radial direction from the particle's body centre
// (bodies[body[i]].center), and the body's pole axis for a particle exactly at the centre.
// Why these numbers: a cancelled sum is rounding noise, not a direction. Measured on a 1M hcp
// ball: |grad c| / sum|terms| is 0.24..0.58 in the outer layer, 0.016..0.17 one spacing in,
// up to 1e-2 two spacings in (the support of 2h = 2.6 s still sees the surface), and noise
// beyond: up to 1.1e-6 with the body at the origin, 5.5e-5 at distance 100 and 7e-4 at 1000
// (float positions: the noise grows as |x| / h). The position term keeps the threshold ~8x
// above that noise, and 1e-5 keeps it above the float arithmetic's noise near the origin.
// Neighbours come from uniform grids, one per octave of h (cells of the octave's largest h),
// so sets whose smoothing lengths span orders of magnitude still cost O(neighbours).
inline constexpr double NORMAL_FALLBACK_RATIO = 1e-5;
void deriveNormals(ParticleSet& particles, std::span<const BodyInfo> bodies);

// glow = blackbodyRadiance(temperature) (blackbody.h).
void deriveGlow(ParticleSet& particles);

}  // namespace twinrender::core
