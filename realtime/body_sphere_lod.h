// realtime.particles.body_sphere_pixels: the level of detail that draws a body small on screen
// as one analytic sphere (core/body_sphere.h) instead of its particles. Chosen per body per
// frame on the CPU from the sphere's projected radius; pure, no GL.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/body_sphere.h"
#include "core/camera.h"

namespace twinrender::realtime {

// The radius in pixels of the sphere's silhouette seen straight ahead: f r / sqrt(D^2 - r^2),
// D the distance to the centre, f the pixels per unit of tangent. Infinite when the eye is
// inside the sphere or its centre is not in front of the eye: such a body is never replaced.
double projectedRadiusPixels(const core::Camera& camera, const glm::dvec3& centre, double radius);

struct BodySphereChoice {
    std::vector<core::BodySphere> drawn;  // the spheres drawn instead of their bodies
    std::vector<bool> replaced;           // per body of the scene: its particles are not drawn
    // Whether a replaced body's supports reach another body's, whose particles they might have
    // hidden: occlusion culling, which counts on every particle, is not exact then.
    bool touchesOthers = false;
};

// The bodies whose sphere (radius > 0) projects below `pixels` (0: none), of `bodyCount`.
BodySphereChoice chooseBodySpheres(std::span<const core::BodySphere> spheres, std::size_t bodyCount,
                                   const core::Camera& camera, double pixels);

// `indices` (every particle of `body` when empty) without the particles of replaced bodies.
std::vector<std::uint32_t> withoutReplaced(std::span<const std::uint32_t> indices,
                                           std::span<const std::uint32_t> body,
                                           const std::vector<bool>& replaced);

}  // namespace twinrender::realtime
