// PNG reading and writing through libpng, without OpenImageIO (oiio_module.h): a comparison of
// two PNGs, the form CI most often hands `twinrender compare`, then never loads OpenImageIO.
// Values are those OpenImageIO gives for the same file, to the bit.
#pragma once

#include <filesystem>
#include <optional>

#include "core/decoded_pixels.h"

namespace twinrender::core {

// True when the file begins with PNG's signature (false when it cannot be opened).
bool isPngFile(const std::filesystem::path& path);

// The pixels of a PNG: palettes expanded to RGB, a transparent colour (tRNS) to an alpha
// channel, grey below 8 bits to 8; 8- and 16-bit values v as v / 255 or v / 65535 (the
// float OpenImageIO computes); colour premultiplied by alpha in integers, as OpenImageIO's PNG
// reader does. Nothing (std::nullopt) for a PNG with alpha and a gAMA chunk, which OpenImageIO
// premultiplies through that gamma: read it with OpenImageIO. Throws InputError naming the
// file and libpng's message when it cannot be read.
std::optional<DecodedPixels> readPng(const std::filesystem::path& path);

// Writes 8-bit RGB (channels 3) or RGBA (channels 4), interleaved, row 0 at the top, at zlib
// level 1 without row filters (a 1920x1080 error map: level 6 took 0.45 s to level 1's
// 0.04 s, for a file 17 % smaller; these images are written once and read by a browser). Throws
// OutputError naming `shownPath` (the file the user asked for; `path` when empty) when it
// cannot be written. Not atomic: writeImage (image_io.h) is.
void writePng(const std::filesystem::path& path, int width, int height, int channels,
              const unsigned char* values, const std::filesystem::path& shownPath = {});

}  // namespace twinrender::core
