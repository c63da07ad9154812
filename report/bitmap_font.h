// A tiny built-in bitmap font (5 x 7 pixels per glyph, one pixel between glyphs) for the text
// drawn into the side-by-side video of a sequence: digits, capital letters (small ones are drawn
// as capitals) and . , : - + = % / ( ) | _ and the space. Drawn by the project, so the video
// needs no font file and looks the same on every machine.
#pragma once

#include <string_view>

#include "core/image.h"

namespace twinrender::report {

constexpr int GLYPH_WIDTH = 5;   // pixels, before scaling
constexpr int GLYPH_HEIGHT = 7;  // pixels, before scaling
constexpr int GLYPH_ADVANCE = GLYPH_WIDTH + 1;

// The width in pixels of `text` drawn at `scale` (each font pixel a scale x scale block).
int textWidth(std::string_view text, int scale);

// Draws `text` into channels R, G, B of `image` with its top left corner at (x, y), each
// font pixel a scale x scale block of `rgb`; what falls outside the image is clipped. A
// character the font lacks is drawn as a hollow box.
void drawText(core::Image& image, int x, int y, std::string_view text, int scale,
              const float rgb[3]);

}  // namespace twinrender::report
