// Where a real-time image's error comes from (docs/design.md, "The error split"): the
// reference's AOV image turned into the real-time renderer's G-buffer and light, so that the
// shade pass can shade the exact surface with the real-time light, or the real-time surface
// with the exact light.
#pragma once

#include "core/image.h"
#include "core/renderer.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

// The reference's surface as a G-buffer (the layout of GBuffer: octahedral normal + uv,
// emission, eye depth + body + radius in pixels + material, and the depth buffer of the depth
// mode), and its light per pixel: the sun's visibility and the ambient occlusion's open
// fraction (R32F each), and the irradiance of emitting surfaces (RGBA32F, rgb; zero without
// light.emissive_light). A pixel is covered where the reference's A > 0; its material is its
// body's, its radius the body's mean h times particles.radius_scale on screen.
struct ExactSurface {
    GBuffer gbuffer;
    gl::Texture visibility;
    gl::Texture ambientOcclusion;
    gl::Texture irradiance;
};
ExactSurface uploadExactSurface(ProgramCache& programs, const core::Image& aov,
                                const core::RenderInput& in, const Settings& settings);

// The CPU side of it: the five RGBA planes (surface, normal + uv, emission, visibility + open
// fraction in r and g, and irradiance), each width x height x 4 floats, rows from the bottom as GL
// stores them. Throws core::NotComparableError when the image lacks a channel or has another size.
struct ExactPlanes {
    std::vector<float> surface, normalUv, emission, light, irradiance;
};
ExactPlanes exactPlanes(const core::Image& aov, const core::RenderInput& in,
                        const Settings& settings);

}  // namespace twinrender::realtime
