// What a surface point takes from the particles around it: the analytic gradient of phi (the
// normal), the kernel weight of each particle, and the uv and glow averaged with those
// weights (u unwrapped at the seam).
#pragma once

#include <cstddef>
#include <glm/vec3.hpp>
#include <vector>

#include "raymarch/particle_batch.h"
#include "raymarch/ray_field.h"

namespace twinrender::raymarch {

// What a surface point averages over the particles around it (kernel weights).
struct HitAttributes {
    float u, v;     // texture coordinates; u wraps around at 1
    float r, g, b;  // glow
};

struct SurfacePoint {
    glm::dvec3 gradient{0.0};  // grad(phi)
    double hMin = 0.0;         // the smallest h of the particles whose support contains it
};

// The kernel weight v_i W(|p - x_i|, h_i) of each candidate of `field` at the ray point p(t)
// into `weights` (0 outside its support; one per candidate, padding included), and grad(phi)
// there. Needs a field from RayField::build().
SurfacePoint surfacePoint(const RayField& field, double t, std::vector<float>& weights);

// The attributes of `batch` (assigned with attributes) averaged with one weight per particle
// of the batch (padding included, 0 for those that do not count; `count` of them, padding
// included), u unwrapped around the heaviest particle's u (the first of equals) so that the
// seam does not average to 0.5. False when no weight is positive.
bool averageAttributes(const ParticleBatch& batch, const float* weights, std::size_t count,
                       HitAttributes& out);

}  // namespace twinrender::raymarch
