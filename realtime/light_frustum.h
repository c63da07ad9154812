// The orthographic shadow-map frustum: the light's view of the scene bounds (the particles'
// support spheres), with the light looking along its direction of travel.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace twinrender::realtime {

struct LightFrustum {
    glm::dmat4 view{1.0};  // camera-relative world -> light eye space (looks down -z), scene units
    glm::dmat4 clip{1.0};  // orthographic projection of the bounds, x and y to [-1, 1]
    double nearDepth = 0.0;  // light-space depth (along the light) stored as 0 in the map
    double farDepth = 1.0;   // ... stored as 1
    double texelSize = 0.0;  // scene units per texel (the larger of the two axes)
};

// `origin`: the camera position (positions on the GPU are relative to it); `direction`: the
// way the light travels (need not be unit); `resolution`: texels per side. The frustum is
// fitted to the eight corners of the bounds plus one texel of margin on each side.
LightFrustum fitLightFrustum(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax,
                             const glm::dvec3& origin, const glm::dvec3& direction, int resolution);

}  // namespace twinrender::realtime
