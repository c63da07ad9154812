#include "core/atmosphere.h"

#include <algorithm>
#include <cmath>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>
#include <vector>

#include "core/body_sphere.h"

namespace twinrender::core {

namespace {

constexpr float PI = 3.14159265358979f;

// The ray's entry t0 and exit t1 of the sphere of `radius` about the origin; false when it
// misses. The discriminant from the distance of the closest point, which keeps its precision
// for a far camera.
bool raySphere(glm::vec3 origin, glm::vec3 direction, float radius, float& t0, float& t1) {
    const float b = glm::dot(origin, direction);
    const glm::vec3 closest = origin - b * direction;
    const float disc = radius * radius - glm::dot(closest, closest);
    if (disc < 0.0f) return false;
    const float s = std::sqrt(disc);
    t0 = -b - s;
    t1 = -b + s;
    return true;
}

float density(const Atmosphere& a, glm::vec3 x) {
    return std::exp(-std::max(glm::length(x) - a.innerRadius, 0.0f) / a.scaleHeight);
}

float henyeyGreenstein(float g, float cosTheta) {
    const float d = 1.0f + g * g - 2.0f * g * cosTheta;
    return (1.0f - g * g) / (4.0f * PI * d * std::sqrt(d));
}

// The transmittance from x toward the sun to the shell's exit; 0 in the inner sphere's shadow.
glm::vec3 sunTransmittance(const Atmosphere& a, const AtmosphereSun& sun, glm::vec3 x) {
    float s0 = 0.0f, s1 = 0.0f;
    if (raySphere(x, sun.toSun, a.innerRadius, s0, s1) && s1 > 0.0f) return glm::vec3(0.0f);
    if (!raySphere(x, sun.toSun, a.outerRadius, s0, s1) || s1 <= 0.0f) return glm::vec3(1.0f);
    const float du = s1 / float(a.steps);
    float depth = 0.0f;
    for (int j = 0; j < a.steps; ++j) depth += density(a, x + (float(j) + 0.5f) * du * sun.toSun);
    const glm::vec3 extinction = a.scattering + a.absorption;
    return glm::exp(-extinction * depth * du);
}

}  // namespace

std::optional<Atmosphere> sceneAtmosphere(const Scene& scene, const SceneParticles& particles,
                                          double surfaceLevel) {
    return sceneAtmosphere(scene, particles, [&](std::uint32_t body) {
        return levelSetRadius(particles.particles, particles.bodies[body], surfaceLevel);
    });
}

std::optional<Atmosphere> sceneAtmosphere(
    const Scene& scene, const SceneParticles& particles,
    const std::function<double(std::uint32_t body)>& levelSetRadiusOf) {
    for (std::uint32_t b = 0; b < scene.bodies.size() && b < particles.bodies.size(); ++b) {
        if (!scene.bodies[b].atmosphere) continue;
        const AtmosphereDesc& d = *scene.bodies[b].atmosphere;
        const BodyBounds bounds = bodyBounds(particles.particles, particles.bodies[b]);
        const double inner = d.radius ? *d.radius : levelSetRadiusOf(b);
        return Atmosphere{.body = b,
                          .centre = bounds.centre,
                          .innerRadius = float(inner),
                          .outerRadius = float(inner + d.thickness),
                          .scaleHeight = float(d.scaleHeight),
                          .scattering = glm::vec3(d.scattering),
                          .absorption = glm::vec3(d.absorption),
                          .phaseG = float(d.phaseG),
                          .steps = d.steps};
    }
    return std::nullopt;
}

AtmosphereSun atmosphereSun(const LightSettings& light) {
    return {.toSun = -glm::normalize(glm::vec3(light.direction)),
            .irradiance = glm::vec3(light.color) * float(light.intensity)};
}

float sphereEntry(glm::vec3 origin, glm::vec3 direction, float radius) {
    float t0 = 0.0f, t1 = 0.0f;
    if (!raySphere(origin, direction, radius, t0, t1) || t0 < 0.0f) return INFINITY;
    return t0;
}

AtmosphereSample integrateAtmosphere(const Atmosphere& a, const AtmosphereSun& sun,
                                     glm::vec3 origin, glm::vec3 direction, float end) {
    AtmosphereSample out;
    float t0 = 0.0f, t1 = 0.0f;
    if (!raySphere(origin, direction, a.outerRadius, t0, t1)) return out;
    t0 = std::max(t0, 0.0f);
    t1 = std::min(t1, end);
    if (!(t1 > t0)) return out;
    const float dt = (t1 - t0) / float(a.steps);
    const glm::vec3 extinction = a.scattering + a.absorption;
    const float phase = henyeyGreenstein(a.phaseG, glm::dot(sun.toSun, direction));
    for (int i = 0; i < a.steps; ++i) {
        const glm::vec3 x = origin + (t0 + (float(i) + 0.5f) * dt) * direction;
        const float rho = density(a, x);
        const glm::vec3 step = glm::exp(-extinction * rho * dt);
        const glm::vec3 scattered =
            a.scattering * rho * phase * sun.irradiance * sunTransmittance(a, sun, x);
        // The step's in-scatter with its transmittance integrated exactly at constant density:
        // (1 - exp(-sigma_t dt)) / sigma_t, dt where nothing attenuates.
        for (int c = 0; c < 3; ++c) {
            const float sigma = extinction[c] * rho;
            const float length = sigma > 0.0f ? (1.0f - step[c]) / sigma : dt;
            out.inscatter[c] += out.transmittance[c] * scattered[c] * length;
        }
        out.transmittance *= step;
    }
    return out;
}

}  // namespace twinrender::core
