// What every metric asks of the pair of images it compares.
#pragma once

#include <string_view>

#include "core/image.h"

namespace twinrender::compare {

// Throws core::NotComparableError, naming `metric`, when the two images differ in size.
void requireSameSize(std::string_view metric, const core::Image& reference,
                     const core::Image& test);

// R, G, B of an image as one interleaved array, 3 floats a pixel: the image's own pixels when
// it holds exactly those channels in that order, else a copy in `storage`.
const float* rgbPixels(const core::Image& image, core::Image& storage);

}  // namespace twinrender::compare
