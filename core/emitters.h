// The emitting bodies of a scene (light.emissive_light): the bodies whose surface emits (an
// emission map or blackbody glow), each with a sphere that bounds its surface. The reference
// samples the cone each sphere subtends from a surface point to integrate the irradiance their
// emission casts (raymarch/emitter_cone.h); the real-time point-light baseline
// (realtime.emissive.method = "point_lights") stands each body in for a glowing sphere.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "core/particles.h"
#include "core/texture.h"

namespace twinrender::core {

struct EmittingBody {
    std::uint32_t body = 0;  // index into SceneParticles::bodies
    // A sphere around every support sphere (position +- 2h) of the body's particles: the
    // surface lies inside it. Its centre is the middle of the supports' bounding box.
    glm::dvec3 centre{0.0};
    double radius = 0.0;
    // The sphere a point light stands in for: the same centre, the particles' distance from it
    // at most, plus half their mean h (about where the level set of a packed ball lies).
    double surfaceRadius = 0.0;
    // The mean emitted radiance of the body's particles (emission map at their uv + glow),
    // linear RGB.
    glm::dvec3 meanRadiance{0.0};
};

// The bodies that emit anywhere (a particle with non-zero emission), in body order.
std::vector<EmittingBody> emittingBodies(const SceneParticles& particles,
                                         const std::vector<Material>& materials);

}  // namespace twinrender::core
