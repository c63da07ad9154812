// An image file's pixels as a reader hands them to readImage (image_io.h), before channels
// are named: libpng's (png_io.h) and OpenImageIO's (oiio_module.h).
#pragma once

#include <string>
#include <vector>

namespace twinrender::core {

// The largest image read: the camera's largest width and height (scene.h), and at most 2^28
// values (1 GiB of floats), so that a damaged header cannot ask for more memory than any
// image the suite writes. Readers check a header against these before allocating.
inline constexpr int MOST_IMAGE_SIDE = 16384;
inline constexpr double MOST_IMAGE_VALUES = 268435456.0;

// "" when an image of this size is read, otherwise why not (for the caller to prefix with the
// path).
inline std::string imageSizeError(double width, double height, double depth, double channels) {
    if (width >= 1.0 && height >= 1.0 && width <= MOST_IMAGE_SIDE && height <= MOST_IMAGE_SIDE &&
        depth <= 1.0 && channels >= 1.0 && width * height * channels <= MOST_IMAGE_VALUES)
        return {};
    return "the image is " + std::to_string(static_cast<long long>(width)) + " x " +
           std::to_string(static_cast<long long>(height)) + " x " +
           std::to_string(static_cast<long long>(depth)) + " pixels with " +
           std::to_string(static_cast<long long>(channels)) +
           " channels; flat images up to 16384 pixels a side and 268435456 values in all are "
           "read (the header may be damaged)";
}

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
