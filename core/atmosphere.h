// The atmosphere of a body (bodies[].atmosphere.*): a thin shell between the body's inner
// sphere (radius R) and the outer sphere (R + thickness), whose density falls as
// exp(-h / scale_height) with the height h above the inner sphere (capped at its value at the
// inner sphere below it). Light is absorbed and scattered once: along a view ray's segment
// [t0, t1] inside the shell, up to its end point (the surface seen, or the shell's exit),
//   T = exp(-integral sigma_t(x) dt),
//   L_in = integral T(t) sigma_s(x) p(theta) E T_sun(x) V(x) dt,
// with p the Henyey-Greenstein phase, E the sun's irradiance (light.intensity x light.color),
// T_sun the transmittance from x toward the sun through the shell and V the inner sphere's
// analytic shadow (0 where the sun ray meets it). What a pixel shows becomes
// surface x T + L_in (the sky: L_in over the whole chord).
//
// One quadrature (`steps` midpoint steps along the view ray and along each sun path, the view
// transmittance integrated exactly over each step at its midpoint's density), in floats,
// mirrored line for line by realtime/shaders/atmosphere.glsl: the two renderers differ only in
// the end point they give it.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/vec3.hpp>
#include <optional>

#include "core/particles.h"
#include "core/scene.h"

namespace twinrender::core {

struct Atmosphere {
    std::uint32_t body = 0;    // index into SceneParticles::bodies
    glm::dvec3 centre{0.0};    // scene units
    float innerRadius = 1.0f;  // scene units
    float outerRadius = 1.1f;
    float scaleHeight = 0.03f;
    glm::vec3 scattering{0.0f};  // sigma_s at the inner sphere, per scene unit
    glm::vec3 absorption{0.0f};  // sigma_a at the inner sphere, per scene unit
    float phaseG = 0.0f;
    int steps = 32;
};

// The scene's atmosphere, if a body has one: its shell about the centre of the body's bounds
// (core/body_sphere.h, bodyBounds), the inner radius atmosphere.radius when given, else the
// body's level-set radius at `surfaceLevel` (levelSetRadius; each renderer gives its own level, the
// raymarcher's raymarch.surface_level and the real-time particles.surface_level, both 0.13 by
// default).
std::optional<Atmosphere> sceneAtmosphere(const Scene& scene, const SceneParticles& particles,
                                          double surfaceLevel);
// The same with the body's level-set radius from `levelSetRadiusOf(body)` (called only where
// atmosphere.radius is not given): a frame loop keeps it while the particles stay the same,
// rather than walk the body's field every frame.
std::optional<Atmosphere> sceneAtmosphere(
    const Scene& scene, const SceneParticles& particles,
    const std::function<double(std::uint32_t body)>& levelSetRadiusOf);

// The sun as the model sees it: the unit direction toward the sun and its irradiance.
struct AtmosphereSun {
    glm::vec3 toSun{0.0f, 0.0f, 1.0f};
    glm::vec3 irradiance{0.0f};
};
AtmosphereSun atmosphereSun(const LightSettings& light);

struct AtmosphereSample {
    glm::vec3 transmittance{1.0f};
    glm::vec3 inscatter{0.0f};  // linear radiance
};

// The ray origin + t direction (direction unit, origin relative to the shell's centre) from
// t = 0 to its end point `end` (INFINITY: no surface; the shell's exit).
AtmosphereSample integrateAtmosphere(const Atmosphere& atmosphere, const AtmosphereSun& sun,
                                     glm::vec3 origin, glm::vec3 direction, float end);

// Where the ray origin + t direction first meets the sphere of `radius` about the origin at
// t >= 0; INFINITY when it does not (or starts inside it).
float sphereEntry(glm::vec3 origin, glm::vec3 direction, float radius);

}  // namespace twinrender::core
