// One pixel of the reference on its way into the AOV image (docs/design.md, "The frame"): each
// sample's hit shaded with the shared model (core/shading.h), the samples of the pixel gathered,
// then the pixel written. Beauty, coverage, emission, shadow, ambient occlusion and irradiance are
// averaged over the samples; the geometric channels (depth, normal, uv, id) are not filtered: they
// come from the hit sample nearest the pixel centre.
#pragma once

#include <cmath>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "core/texture.h"
#include "raymarch/surface_tracer.h"

namespace twinrender::raymarch {

// A hit sample, shaded: linear radiance and the emission buffer's value (emission map + glow).
struct ShadedSample {
    glm::vec3 beauty{0.0f};
    glm::vec3 emission{0.0f};
};

// Shades a hit seen along `direction` (the camera ray's, unit), lit with `visibility` (1 lit,
// 0 in shadow), its ambient term times `ambientOcclusion` (the open fraction, 1: none), with
// `irradiance` from emitting surfaces (linear RGB).
ShadedSample shadeHit(const SurfaceHit& hit, const glm::dvec3& direction, float visibility,
                      const std::vector<core::Material>& materials,
                      const core::LightSettings& light, float ambientOcclusion = 1.0f,
                      glm::vec3 irradiance = glm::vec3(0.0f));

// The hit samples of one pixel. Pixels are independent and each sums its samples in sample
// order, so the image does not depend on the order in which pixels are traced.
struct PixelSamples {
    glm::dvec3 beauty{0.0};  // sums over the hit samples
    glm::dvec3 emission{0.0};
    double coverage = 0.0;  // hit samples
    double shadow = 0.0;
    double ambientOcclusion = 0.0;
    glm::dvec3 irradiance{0.0};
    // The atmosphere's in-scatter (core/atmosphere.h) over every sample, hit or not; the beauty
    // holds it too.
    glm::dvec3 inscatter{0.0};
    // The kept geometric channels and the squared distance of their sample from the pixel
    // centre, in pixels.
    double nearest = INFINITY;
    float depth = 0.0f;  // eye depth along the view axis
    glm::vec3 normal{0.0f};
    glm::vec2 uv{0.0f};
    float body = 0.0f;

    // Adds the hit sample at (jx, jy) in the pixel ([0, 1)^2, centre 0.5) whose eye depth is
    // `depth`, its ambient occlusion's open fraction `ambientOcclusion`, its irradiance from
    // emitting surfaces `irradiance`.
    void add(const ShadedSample& sample, float visibility, const SurfaceHit& hit, double depth,
             double jx, double jy, float ambientOcclusion = 1.0f,
             glm::vec3 irradiance = glm::vec3(0.0f));
    // Adds a sample that met no surface but saw the atmosphere's in-scatter.
    void addSky(glm::vec3 light);
};

// The indices of the AOV channels a pixel writes, looked up once per frame.
struct AovChannels {
    explicit AovChannels(const core::Image& image);
    int beauty, coverage, depth, normal, uv, id, emission, shadow, ao, irradiance,
        inscatter;  // R, A, Z, N.X, uv.U, ...
};

// Writes pixel (x, y) of the AOV image (`spp` samples per pixel) and of the display image (R, G,
// B; core::tonemap of the beauty). Both images are new (zero): a pixel without a hit sample
// gets the background of core::aov::makeImage by its Z = +inf and id = -1 alone, and the
// atmosphere's in-scatter its samples saw as its beauty.
void writePixel(const PixelSamples& samples, int spp, float exposure, int x, int y,
                const AovChannels& channels, core::Image& aov, core::Image& display);

}  // namespace twinrender::raymarch
