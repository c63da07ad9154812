// The old shadow baseline (realtime.shadows = "spheres"): every body holding more than 5 % of
// the particles casts the shadow of one sphere at its centre of mass with its effective radius.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "core/particles.h"

namespace twinrender::realtime {

struct OcclusionSphere {
    glm::dvec3 centre;  // centre of mass: the volume-weighted mean position, scene units
    double radius = 0;  // effective radius: of the ball with the body's total volume sum(v)
    std::uint32_t body = 0;
};

constexpr double OCCLUSION_MIN_FRACTION = 0.05;

// Bodies with more than minFraction of all particles, in body order.
std::vector<OcclusionSphere> occlusionSpheres(const core::SceneParticles& scene,
                                              double minFraction = OCCLUSION_MIN_FRACTION);

}  // namespace twinrender::realtime
