// What a device's name says about it: the GL_RENDERER strings of the software rasterisers,
// on which the real-time renderer runs on the CPU (its times are then not a GPU's).
#pragma once

#include <string_view>

namespace twinrender::core {

// True for a CPU rasteriser's GL_RENDERER: llvmpipe, softpipe, swrast, SwiftShader.
inline bool isSoftwareRasteriser(std::string_view glRenderer) {
    for (std::string_view name : {"llvmpipe", "softpipe", "swrast", "SwiftShader"})
        if (glRenderer.find(name) != std::string_view::npos) return true;
    return false;
}

}  // namespace twinrender::core
