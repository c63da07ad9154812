// The last step of a real-time frame: the buffers read back from GL become the AOV image of
// docs/design.md and the display image. Pure CPU, no GL: the renderer reads the textures, this
// turns OpenGL's bottom-up rows of RGBA floats into the images' top-down channels.
#pragma once

#include <span>

#include "core/image.h"

namespace twinrender::realtime {

// Each buffer holds width x height RGBA floats, bottom row first (as glReadPixels gives them).
struct ReadBackBuffers {
    int width = 0, height = 0;
    std::span<const float> normalUv;      // octahedral world normal (octahedral.h), u, v
    std::span<const float> emission;      // emission rgb; empty: the scene emits nowhere (all 0)
    std::span<const float> surface;       // eye depth, body (< 0 on the background), -, -
    std::span<const float> beautyShadow;  // linear beauty rgb, light visibility
    std::span<const float> display;       // display rgb (bloom, tonemapped), -
    // The ambient occlusion's open fraction, one float a pixel; empty: no occlusion (1).
    std::span<const float> ambientOcclusion;
    // The irradiance from emitting surfaces (light.emissive_light), rgb and one unused float a
    // pixel; empty: none (0).
    std::span<const float> irradiance;
    // The atmosphere's in-scatter, rgb and one unused float a pixel, the beauty holding it on
    // the background too; empty: no atmosphere (0, and a black background).
    std::span<const float> inscatter;
};

// Writes every pixel of `aov` (the core::aov channels; core::aov::makeImage's values on the
// background, but for the beauty: a halo, particles.halo_pixels, may light it) and of
// `display` (R, G, B). Both must have the buffers' size; their old values
// (a recycled frame's) are all overwritten.
void assembleFrame(const ReadBackBuffers& buffers, core::Image& aov, core::Image& display);

}  // namespace twinrender::realtime
