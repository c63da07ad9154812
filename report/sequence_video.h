// The frames of a sequence's side-by-side video: real-time | reference | ꟻLIP map, each panel
// labelled, and under them a caption with the frame number and a running metric, drawn with
// the built-in bitmap font (bitmap_font.h). The encoder (app/video_encoder.h) takes them as
// 8-bit RGB.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"

namespace twinrender::report {

// The video frame of one sequence frame. `realtime` and `reference` are display images
// (sRGB R, G, B in [0, 1]) of one size; `flipMap` is ꟻLIP's per-pixel error (channel 0, in
// [0, 1]) of that size, shown through magma, side by side under a band holding `caption`.
// Width and height are even (H.264's yuv420p needs them so); the text is scaled with the
// panels. Throws core::NotComparableError for sizes that differ.
core::Image sideBySideFrame(const core::Image& realtime, const core::Image& reference,
                            const core::Image& flipMap, const std::string& caption);

// R, G, B of an image in [0, 1] as interleaved 8-bit RGB, rounded; what an encoder reads.
std::vector<std::uint8_t> rgb8(const core::Image& image);

}  // namespace twinrender::report
