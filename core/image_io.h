// Image reading and writing: PNG through libpng (png_io.h), EXR and every other format through
// OpenImageIO, loaded on first use (oiio_module.h). Every write goes to a temporary name
// beside the target and is renamed into place, so a failed run leaves no partial file.
#pragma once

#include <filesystem>
#include <functional>
#include <utility>

#include "core/image.h"

namespace twinrender::core {

// Reads a PNG, or any image OpenImageIO understands. EXR channels keep their names and float
// values; 8- and 16-bit images (PNG) become R, G, B (and A) in [0, 1], as stored (no decoding of
// sRGB). Throws InputError naming the file when it cannot be read.
Image readImage(const std::filesystem::path& path);

// Reads two images at once, each on its own thread (decoding a 1920x1080 PNG takes about
// 50 ms). When both fail, the first one's error is thrown.
std::pair<Image, Image> readImages(const std::filesystem::path& first,
                                   const std::filesystem::path& second);

// Writes by extension: ".exr" writes every channel as float32 (zip compression); ".png"
// writes R, G, B (and A when present) clamped to [0, 1] and quantised to 8 bits, values as
// given (the caller tonemaps and encodes). Atomic: temporary name, then rename.
void writeImage(const Image& image, const std::filesystem::path& path);

// Calls write(tmp) with a temporary path beside `path` that keeps its extension, then renames
// tmp to path. On any exception the temporary file is removed and the exception rethrown.
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tmp)>& write);

// Writes a text file atomically.
void writeTextFile(const std::filesystem::path& path, std::string_view text);

}  // namespace twinrender::core
