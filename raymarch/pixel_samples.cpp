#include "raymarch/pixel_samples.h"

#include <limits>

#include "core/shading.h"

namespace twinrender::raymarch {

ShadedSample shadeHit(const SurfaceHit& hit, const glm::dvec3& direction, float visibility,
                      const std::vector<core::Material>& materials,
                      const core::LightSettings& light, float ambientOcclusion,
                      glm::vec3 irradiance) {
    core::SurfacePoint sp;
    sp.normal = hit.normal;
    sp.toEye = glm::vec3(-direction);
    sp.uv = hit.uv;
    sp.material = hit.material;
    sp.emission = core::surfaceEmission(materials[hit.material], hit.uv, hit.glow);
    sp.visibility = visibility;
    sp.ambientOcclusion = ambientOcclusion;
    sp.irradiance = irradiance;
    return {core::shade(materials, light, sp), sp.emission};
}

void PixelSamples::add(const ShadedSample& sample, float visibility, const SurfaceHit& hit,
                       double hitDepth, double jx, double jy, float open, glm::vec3 light) {
    beauty += glm::dvec3(sample.beauty);
    emission += glm::dvec3(sample.emission);
    coverage += 1.0;
    shadow += visibility;
    ambientOcclusion += open;
    irradiance += glm::dvec3(light);
    const double dist = (jx - 0.5) * (jx - 0.5) + (jy - 0.5) * (jy - 0.5);
    if (dist < nearest) {
        nearest = dist;
        depth = static_cast<float>(hitDepth);
        normal = hit.normal;
        uv = hit.uv;
        body = static_cast<float>(hit.body);
    }
}

void PixelSamples::addSky(glm::vec3 light) {
    beauty += glm::dvec3(light);
    inscatter += glm::dvec3(light);
}

AovChannels::AovChannels(const core::Image& image)
    : beauty(image.requireChannel("R")),
      coverage(image.requireChannel("A")),
      depth(image.requireChannel("Z")),
      normal(image.requireChannel("N.X")),
      uv(image.requireChannel("uv.U")),
      id(image.requireChannel("id")),
      emission(image.requireChannel("emission.R")),
      shadow(image.requireChannel("shadow")),
      ao(image.requireChannel("ao")),
      irradiance(image.requireChannel("irradiance.R")),
      inscatter(image.requireChannel("inscatter.R")) {}

namespace {

// The beauty, the in-scatter it holds and the beauty's display value.
void writeLight(glm::vec3 beauty, glm::dvec3 inscatter, float exposure, int x, int y,
                const AovChannels& c, core::Image& aov, core::Image& display) {
    const glm::vec3 shown = core::tonemap(beauty, exposure);
    for (int k = 0; k < 3; ++k) {
        aov.at(x, y, c.beauty + k) = beauty[k];
        aov.at(x, y, c.inscatter + k) = static_cast<float>(inscatter[k]);
        display.at(x, y, k) = shown[k];
    }
}

}  // namespace

void writePixel(const PixelSamples& s, int spp, float exposure, int x, int y, const AovChannels& c,
                core::Image& aov, core::Image& display) {
    const double inv = 1.0 / spp;
    glm::vec3 beauty;
    for (int k = 0; k < 3; ++k) beauty[k] = static_cast<float>(s.beauty[k] * inv);
    if (s.coverage == 0.0) {
        aov.at(x, y, c.depth) = std::numeric_limits<float>::infinity();
        aov.at(x, y, c.id) = -1.0f;
        if (s.inscatter == glm::dvec3(0.0)) return;
        // The sky seen through an atmosphere.
        writeLight(beauty, s.inscatter * inv, exposure, x, y, c, aov, display);
        return;
    }
    for (int k = 0; k < 3; ++k) {
        aov.at(x, y, c.emission + k) = static_cast<float>(s.emission[k] / s.coverage);
        aov.at(x, y, c.normal + k) = s.normal[k];
        aov.at(x, y, c.irradiance + k) = static_cast<float>(s.irradiance[k] / s.coverage);
    }
    aov.at(x, y, c.coverage) = static_cast<float>(s.coverage * inv);
    aov.at(x, y, c.shadow) = static_cast<float>(s.shadow / s.coverage);
    aov.at(x, y, c.ao) = static_cast<float>(s.ambientOcclusion / s.coverage);
    aov.at(x, y, c.depth) = s.depth;
    aov.at(x, y, c.uv) = s.uv.x;
    aov.at(x, y, c.uv + 1) = s.uv.y;
    aov.at(x, y, c.id) = s.body;
    writeLight(beauty, s.inscatter * inv, exposure, x, y, c, aov, display);
}

}  // namespace twinrender::raymarch
