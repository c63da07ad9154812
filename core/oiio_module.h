// OpenImageIO behind a module loaded on first use (core/oiio/image_io_oiio.cpp, the shared
// module twinrender_oiio). Debian's OpenImageIO brings 266 shared libraries; linked into the
// program, the dynamic loader spends about 0.18 s of CPU binding their symbols at every
// start, before main. Loaded when the first EXR (or other non-PNG image) is read or written,
// a process that handles only PNGs (libpng, png_io.h) never pays it.
#pragma once

#include <string>
#include <vector>

#include "core/decoded_pixels.h"

namespace twinrender::core::oiio {

// What the module offers. Each function returns "" on success, otherwise what went wrong (with
// OpenImageIO's message) for the caller to prefix with the path; none throws.
struct Api {
    std::string (*read)(const std::string& path, DecodedPixels& out);
    // Every channel as float32, zip-compressed (EXR); alpha and z are channel indices or -1.
    std::string (*writeFloat)(const std::string& path, int width, int height,
                              const std::vector<std::string>& channelNames, int alpha, int z,
                              const float* values);
    // 8-bit values, `channels` a pixel (the fourth one alpha), the format by the extension.
    std::string (*writeBytes)(const std::string& path, int width, int height, int channels,
                              const unsigned char* values);
};

// The module's entry point: the symbol looked up after loading it.
inline constexpr const char* ENTRY_POINT = "twinrender_oiio_api";
using EntryPoint = const Api* (*)();

// Loads the module on the first call (thread-safe) and returns its functions. Throws
// InputError naming the module's path when it cannot be loaded.
const Api& api();

}  // namespace twinrender::core::oiio
