#include "core/shading.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace twinrender::core {

glm::vec3 surfaceEmission(const Material& material, glm::vec2 uv, glm::vec3 glow) {
    return material.emission.sample(uv) + glow;
}

float nightFactor(glm::vec3 normal, glm::vec3 towardLight) {
    // A 0.2-wide band in n.l around the terminator, so city lights fade in at dusk.
    return std::clamp(0.5f - 5.0f * glm::dot(normal, towardLight), 0.0f, 1.0f);
}

glm::vec3 shade(const std::vector<Material>& materials, const LightSettings& light,
                const SurfacePoint& p) {
    const Material& m = materials[p.material];
    const glm::vec3 l = -glm::vec3(light.direction);
    const glm::vec3 lightColor = glm::vec3(light.color) * float(light.intensity);
    const glm::vec3 albedo = m.diffuse.sample(p.uv);
    const float nl = glm::dot(p.normal, l);
    glm::vec3 color = albedo * glm::vec3(light.color) * float(light.ambient) * p.ambientOcclusion;
    color += albedo * p.irradiance * float(1.0 / 3.14159265358979323846);
    if (nl > 0.0f) {
        const glm::vec3 halfway = glm::normalize(l + p.toEye);
        const float nh = std::max(glm::dot(p.normal, halfway), 0.0f);
        const glm::vec3 specular = m.specular.sample(p.uv) * std::pow(nh, m.shininess);
        color += (albedo * nl + specular) * lightColor * p.visibility;
    }
    color += p.emission;
    color += m.cityLights.sample(p.uv) * nightFactor(p.normal, l);
    return color;
}

float linearToSrgb(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float srgbToLinear(float v) {
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

glm::vec3 tonemap(glm::vec3 linear, float exposure) {
    // ACES filmic approximation, Narkowicz 2015, "ACES Filmic Tone Mapping Curve".
    constexpr float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        const float x = std::max(linear[i] * exposure, 0.0f);
        out[i] = linearToSrgb(std::clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0f, 1.0f));
    }
    return out;
}

}  // namespace twinrender::core
