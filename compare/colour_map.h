// The colour map of the report's error images: matplotlib's magma (CC0, van der Walt and
// Smith), perceptually uniform, from black through purple and orange to pale yellow.
#pragma once

#include <filesystem>
#include <string>

#include "core/image.h"

namespace twinrender::compare {

// t in [0, 1] -> sRGB display value in [0, 1]; t is clamped, NaN is 0.
void magma(double t, float rgb[3]);

// Channel `channel` of `map` mapped from [lo, hi] through magma; NaN pixels are black.
// Throws std::invalid_argument for a channel the image does not have.
core::Image colourMapped(const core::Image& map, int channel, double lo, double hi);

// colourMapped(...) written as PNG (atomically).
void writeErrorMapPng(const core::Image& map, int channel, double lo, double hi,
                      const std::filesystem::path& png);

// The map as a CSS linear-gradient from left (0) to right (1), for a colour bar beside an
// error image.
std::string magmaCssGradient();

}  // namespace twinrender::compare
