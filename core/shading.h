// The shading model both renderers use (mirrored in realtime/shaders/shading.glsl): Lambert
// diffuse x diffuse texture, Blinn-Phong specular x specular map, the emission buffer
// (emission map + blackbody glow), city lights on the night side only, ambient times its occlusion,
// the light of emitting surfaces (albedo x irradiance / pi).
// The directional light is multiplied by its visibility (shadow). Linear radiance out.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "core/scene.h"
#include "core/texture.h"

namespace twinrender::core {

struct SurfacePoint {
    glm::vec3 normal;  // unit, world space
    glm::vec3 toEye;   // unit, from the surface to the camera
    glm::vec2 uv;
    std::uint32_t material = 0;
    glm::vec3 emission{0.0f};  // emission map + glow, already looked up
    float visibility = 1.0f;   // 1 lit, 0 in shadow
    // The ambient occlusion: the cosine-weighted fraction of the hemisphere open within
    // light.ao_radius (1 open, 0 closed). It multiplies the ambient term.
    float ambientOcclusion = 1.0f;
    // Linear RGB irradiance from emitting surfaces (light.emissive_light), added as
    // albedo * irradiance / pi: the Lambert reflection of that light.
    glm::vec3 irradiance{0.0f};
};

// Emission map at uv plus the particle glow: the value of the emission buffer.
glm::vec3 surfaceEmission(const Material& material, glm::vec2 uv, glm::vec3 glow);

// Weight of the city lights: 1 on the night side (n.l <= -0.1), 0 on the day side
// (n.l >= 0.1), linear between. `towardLight` is the unit vector to the sun.
float nightFactor(glm::vec3 normal, glm::vec3 towardLight);

glm::vec3 shade(const std::vector<Material>& materials, const LightSettings& light,
                const SurfacePoint& p);

// Exposure, then the ACES filmic curve (Narkowicz 2015 fit), then the sRGB transfer function:
// linear radiance -> display value in [0, 1].
glm::vec3 tonemap(glm::vec3 linear, float exposure);
// The sRGB transfer functions (IEC 61966-2-1).
float linearToSrgb(float v);
float srgbToLinear(float v);

}  // namespace twinrender::core
