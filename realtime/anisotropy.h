// Ellipsoid impostors from each particle's neighbourhood (realtime.particles.shape =
// "ellipsoid"): the anisotropic kernels of Yu & Turk 2013 ("Reconstructing Surfaces of
// Particle-Based Fluids Using Anisotropic Kernels", ACM TOG 32(1)). For particle i with
// neighbours j within r_i = 2 h_i (i itself included in the sums, weight 1):
//   w_ij = 1 - (|x_j - x_i| / r_i)^3,   x_i^w = sum_j w_ij x_j / sum_j w_ij,
//   C_i = sum_j w_ij (x_j - x_i^w)(x_j - x_i^w)^T / sum_j w_ij = R diag(s_1 >= s_2 >= s_3) R^T,
// the smoothed centre x_i + lambda (x_i^w - x_i), and the clamped spread
//   S_i = diag(s_1, max(s_2, s_1 / k_r), max(s_3, s_1 / k_r)),
// whose entries the paper's kernel takes as its axis lengths (G_i = R S_i^-1 R^T / h_i, times
// a scale k_s = 1400 that assumes its scenes' units).
//
// Here the size is scale-free and the impostor radius r (realtime/impostor_radius.h) keeps
// deciding it: the axis lengths are r times S_i normalised to a unit product,
// a_k = r s_k / cbrt(s_1 s_2 s_3), so an ellipsoid has the volume of the sphere it replaces
// (an isolated particle stays the level set's small droplet, one without a surface is not
// drawn). Drawn as they are, the kernels of a body's outer layer lie inside the level set:
// flattened across the surface (their short axis 0.4 r at k_r = 4) and pulled inwards by
// the smoothing (about half their neighbourhood's offset, 0.3-0.5 h), they end most of a
// radius below where the spheres ended. With anchor = "surface" (the default) each ellipsoid
// is then moved along its particle's normal until it reaches as far along it as the sphere:
// the surface stays where the radius model put it (the level set, with field radii), and
// the smoothing acts along the surface only. anchor = "centre" keeps the paper's placement.
// A particle with fewer than N_eps neighbours, or whose neighbours all coincide with it, stays
// that sphere, about its own position.
//
// The raymarcher's isotropic level set stays the truth: an ellipsoid flattened along a flat
// neighbourhood's normal (ratio k_r in a single layer) approximates a flat surface better than
// the bumps of spheres.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "core/particles.h"
#include "realtime/particle_set_key.h"
#include "realtime/settings.h"

namespace twinrender::realtime {

// The ellipsoid {centre + A u : |u| <= 1}, centre = the particle's position + shift, A's
// columns the semi-axis vectors (orthogonal, world space, scene units).
struct Ellipsoid {
    glm::vec3 shift{0.0f};
    glm::vec3 axes[3] = {};

    // Whether it is a sphere of radius r about the particle.
    bool isSphere() const;
    // The sphere of radius r about the particle.
    static Ellipsoid sphere(float r);
};

// One ellipsoid per particle of the set; radii[i] is particle i's impostor radius (the
// sphere of the same volume). The result does not depend on the thread count.
std::vector<Ellipsoid> anisotropicEllipsoids(const core::ParticleSet& particles,
                                             std::span<const float> radii,
                                             const AnisotropySettings& settings);

// anisotropicEllipsoids with the last answer kept: the ellipsoids depend on the particles
// (positions, h), the impostor radii and the settings, not on the view, so the frames of an
// unchanged set reuse them (inputs kept and compared exactly, ParticleSetKey).
class AnisotropyCache {
  public:
    const std::vector<Ellipsoid>& ellipsoids(const core::ParticleSet& particles,
                                             std::span<const float> radii,
                                             const AnisotropySettings& settings);
    bool reused() const { return mCache.reused(); }

  private:
    SetCache<std::vector<Ellipsoid>, std::span<const float>, AnisotropySettings> mCache;
};

}  // namespace twinrender::realtime
