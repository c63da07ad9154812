#include "realtime/frame_assembly.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

#include "realtime/octahedral.h"

namespace twinrender::realtime {

void assembleFrame(const ReadBackBuffers& in, core::Image& aov, core::Image& display) {
    const int w = in.width, h = in.height;
    const auto channel = [&](const char* name) { return aov.requireChannel(name); };
    const int cR = channel("R"), cG = channel("G"), cB = channel("B"), cA = channel("A"),
              cZ = channel("Z"), cNX = channel("N.X"), cNY = channel("N.Y"), cNZ = channel("N.Z"),
              cU = channel("uv.U"), cV = channel("uv.V"), cId = channel("id"),
              cER = channel("emission.R"), cEG = channel("emission.G"), cEB = channel("emission.B"),
              cShadow = channel("shadow"), cAo = channel("ao"), cIR = channel("irradiance.R"),
              cIG = channel("irradiance.G"), cIB = channel("irradiance.B"),
              cSR = channel("inscatter.R");
    const std::size_t stride = static_cast<std::size_t>(aov.channelCount());
    const bool emits = !in.emission.empty();
    const bool occluded = !in.ambientOcclusion.empty();
    const bool irradiated = !in.irradiance.empty();
    const bool scattered = !in.inscatter.empty();
    float* out = aov.pixels().data();
    float* shown = display.pixels().data();
    // The background values of core::aov::makeImage (Z = +inf, id = -1, the rest 0) are
    // written in the same pass as the covered pixels: filling the channels first costs
    // as much as the whole read-back.
    tbb::parallel_for(0, h, [&](int y) {
        // OpenGL rows run bottom-up; images top-down.
        const std::size_t glRow = static_cast<std::size_t>(h - 1 - y) * w;
        for (int x = 0; x < w; ++x) {
            const std::size_t g = (glRow + x) * 4;
            const std::size_t p = static_cast<std::size_t>(y) * w + x;
            float* d = shown + p * 3;
            d[0] = in.display[g + 0];
            d[1] = in.display[g + 1];
            d[2] = in.display[g + 2];
            const float body = in.surface[g + 1];
            float* o = out + p * stride;
            if (body < 0.0f) {
                std::fill(o, o + stride, 0.0f);  // a recycled image holds an older frame
                o[cZ] = std::numeric_limits<float>::infinity();
                o[cId] = -1.0f;
                // The shade pass leaves the background black; a sub-pixel emitter's halo
                // (particles.halo_pixels) may light it, and the sky seen through an atmosphere.
                o[cR] = in.beautyShadow[g + 0];
                o[cG] = in.beautyShadow[g + 1];
                o[cB] = in.beautyShadow[g + 2];
                if (scattered)
                    for (int c = 0; c < 3; ++c) o[cSR + c] = in.inscatter[g + c];
                continue;
            }
            o[cR] = in.beautyShadow[g + 0];
            o[cG] = in.beautyShadow[g + 1];
            o[cB] = in.beautyShadow[g + 2];
            o[cShadow] = in.beautyShadow[g + 3];
            o[cAo] = occluded ? std::min(in.ambientOcclusion[glRow + x], 1.0f) : 1.0f;  // as shaded
            o[cA] = 1.0f;
            o[cZ] = in.surface[g + 0];
            o[cId] = body;
            const glm::vec3 n = octDecode({in.normalUv[g + 0], in.normalUv[g + 1]});
            o[cNX] = n.x;
            o[cNY] = n.y;
            o[cNZ] = n.z;
            o[cU] = in.normalUv[g + 2];
            o[cV] = in.normalUv[g + 3];
            o[cER] = emits ? in.emission[g + 0] : 0.0f;
            o[cEG] = emits ? in.emission[g + 1] : 0.0f;
            o[cEB] = emits ? in.emission[g + 2] : 0.0f;
            o[cIR] = irradiated ? in.irradiance[g + 0] : 0.0f;
            o[cIG] = irradiated ? in.irradiance[g + 1] : 0.0f;
            o[cIB] = irradiated ? in.irradiance[g + 2] : 0.0f;
            for (int c = 0; c < 3; ++c) o[cSR + c] = scattered ? in.inscatter[g + c] : 0.0f;
        }
    });
}

}  // namespace twinrender::realtime
