#include "report/sequence_video.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "report/bitmap_font.h"

namespace twinrender::report {
namespace {

core::Image filled(int w, int h, float v) {
    core::Image im(w, h, {"R", "G", "B"});
    for (float& x : im.pixels()) x = v;
    return im;
}

TEST(SequenceVideo, ThreePanelsSideBySideWithTextAndEvenSize) {
    const core::Image rt = filled(33, 25, 0.25f), ref = filled(33, 25, 0.5f);
    core::Image map(33, 25, {"flip"});
    const core::Image frame = sideBySideFrame(rt, ref, map, "FRAME 7");
    EXPECT_EQ(frame.width() % 2, 0);
    EXPECT_EQ(frame.height() % 2, 0);
    EXPECT_GE(frame.width(), 3 * 33);
    EXPECT_GT(frame.height(), 25);
    // The caption's band is on top (a paused player's controls cover the bottom): the panels
    // sit under it, their pixels away from the labels (bottom right of each panel) unchanged.
    const int band = GLYPH_HEIGHT + 4;  // the font at scale 1 (25 rows / 80, rounded up to 1)
    EXPECT_EQ(frame.height(), band + 25 + (band + 25) % 2);
    EXPECT_FLOAT_EQ(frame.at(32, band + 24, 0), 0.25f);
    EXPECT_FLOAT_EQ(frame.at(33 + 2 + 32, band + 24, 0), 0.5f);
    // The caption: some bright pixels in the band.
    int lit = 0;
    for (int y = 0; y < band; ++y)
        for (int x = 0; x < frame.width(); ++x) lit += frame.at(x, y, 0) > 0.5f;
    EXPECT_GT(lit, 20);
    EXPECT_THROW(sideBySideFrame(rt, filled(32, 25, 0.f), map, ""), core::NotComparableError);
}

TEST(BitmapFont, DrawsGlyphsAtTheirPlace) {
    core::Image im = filled(20, 9, 0.0f);
    const float white[3] = {1.0f, 1.0f, 1.0f};
    drawText(im, 1, 1, "1", 1, white);
    // The digit 1's stem: column 2 of the glyph, rows 0 to 6.
    for (int y = 1; y <= 7; ++y) EXPECT_EQ(im.at(3, y, 0), 1.0f) << y;
    EXPECT_EQ(im.at(1, 1, 0), 0.0f);
    EXPECT_EQ(textWidth("AB", 2), (2 * GLYPH_ADVANCE - 1) * 2);
    // Lower case is drawn as capitals; text past the edge is clipped.
    core::Image a = filled(20, 9, 0.0f), b = filled(20, 9, 0.0f);
    drawText(a, 0, 0, "ab", 1, white);
    drawText(b, 0, 0, "AB", 1, white);
    EXPECT_EQ(a, b);
    drawText(b, 15, 5, "WWW", 1, white);
}

TEST(SequenceVideo, Rgb8RoundsAndClamps) {
    core::Image im(2, 1, {"R", "G", "B"});
    im.at(0, 0, 0) = 1.5f;
    im.at(0, 0, 1) = 0.5f;
    im.at(0, 0, 2) = -1.0f;
    im.at(1, 0, 0) = NAN;
    const auto bytes = rgb8(im);
    EXPECT_EQ(bytes, (std::vector<std::uint8_t>{255, 128, 0, 0, 0, 0}));
}

}  // namespace
}  // namespace twinrender::report
