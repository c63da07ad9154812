#include "report/sequence_video.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "compare/colour_map.h"
#include "core/error.h"
#include "report/bitmap_font.h"

namespace twinrender::report {

using compare::colourMapped;

namespace {

constexpr int GAP_PX = 2;  // dark line between the panels

// Copies channels R, G, B of `from` into `to` with its top left corner at (x0, y0).
void blit(const core::Image& from, core::Image& to, int x0, int y0) {
    const int fr = from.requireChannel("R");
    for (int y = 0; y < from.height(); ++y)
        for (int x = 0; x < from.width(); ++x)
            for (int c = 0; c < 3; ++c) to.at(x0 + x, y0 + y, c) = from.at(x, y, fr + c);
}

// Text on a dark box, so that it reads on any image.
void label(core::Image& image, int x, int y, const std::string& text, int scale) {
    const int pad = scale;
    const int w = textWidth(text, scale) + 2 * pad, h = GLYPH_HEIGHT * scale + 2 * pad;
    for (int py = std::max(y, 0); py < std::min(y + h, image.height()); ++py)
        for (int px = std::max(x, 0); px < std::min(x + w, image.width()); ++px)
            for (int c = 0; c < 3; ++c) image.at(px, py, c) *= 0.35f;
    const float white[3] = {1.0f, 1.0f, 1.0f};
    drawText(image, x + pad, y + pad, text, scale, white);
}

}  // namespace

core::Image sideBySideFrame(const core::Image& realtime, const core::Image& reference,
                            const core::Image& flipMap, const std::string& caption) {
    const int w = realtime.width(), h = realtime.height();
    for (const core::Image* im : {&reference, &flipMap})
        if (im->width() != w || im->height() != h)
            throw core::NotComparableError(fmt::format("video panels of {}x{} and {}x{} pixels", w,
                                                       h, im->width(), im->height()));
    // The font's pixel: about 1/80 of the panel's height, at least 1.
    const int scale = std::max(1, static_cast<int>(std::lround(h / 80.0)));
    const int band = GLYPH_HEIGHT * scale + 4 * scale;
    const int width = 3 * w + 2 * GAP_PX, height = h + band;
    core::Image frame(width + width % 2, height + height % 2, {"R", "G", "B"});
    // The caption's band on top: a paused player draws its controls over the bottom of the
    // picture, where a caption would be hidden.
    blit(realtime, frame, 0, band);
    blit(reference, frame, w + GAP_PX, band);
    blit(colourMapped(flipMap, 0, 0.0, 1.0), frame, 2 * (w + GAP_PX), band);
    const int margin = scale;
    label(frame, margin, band + margin, "REAL-TIME", scale);
    label(frame, w + GAP_PX + margin, band + margin, "REFERENCE", scale);
    label(frame, 2 * (w + GAP_PX) + margin, band + margin, "FLIP", scale);
    const float grey[3] = {0.85f, 0.85f, 0.85f};
    drawText(frame, margin, 2 * scale, caption, scale, grey);
    return frame;
}

std::vector<std::uint8_t> rgb8(const core::Image& image) {
    const int r = image.requireChannel("R"), g = image.requireChannel("G"),
              b = image.requireChannel("B");
    std::vector<std::uint8_t> out(image.pixelCount() * 3);
    for (std::size_t p = 0; p < image.pixelCount(); ++p)
        for (int c = 0; c < 3; ++c) {
            const float v = image.at(p, c == 0 ? r : c == 1 ? g : b);
            out[3 * p + c] = static_cast<std::uint8_t>(
                std::lround(std::clamp(std::isnan(v) ? 0.0f : v, 0.0f, 1.0f) * 255.0f));
        }
    return out;
}

}  // namespace twinrender::report
