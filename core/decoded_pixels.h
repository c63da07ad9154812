// An image file's pixels as a reader hands them to readImage (image_io.h), before channels
// are named: libpng's (png_io.h) and OpenImageIO's (oiio_module.h).
#pragma once

#include <string>
#include <vector>

namespace twinrender::core {

struct DecodedPixels {
    int width = 0;
    int height = 0;
    // As the file names them ("" where it names none); plain images are named by position.
    std::vector<std::string> channelNames;
    // Float or half values in the file (an EXR); false for 8- and 16-bit integers, which
    // arrive as value / (2^bits - 1), colour premultiplied by alpha as OpenImageIO does.
    bool isFloat = false;
    // Channels interleaved, row 0 at the top.
    std::vector<float> values;
};

}  // namespace twinrender::core
