#include "compare/masks.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/frame.h"

namespace twinrender::compare {
namespace {

// Marks pixel (x, y) covered by body `id` with normal n.
void cover(core::Image& img, int x, int y, float id, float nx = 0, float ny = 0, float nz = 1) {
    img.at(x, y, img.channelIndex("A")) = 1.0f;
    img.at(x, y, img.channelIndex("Z")) = 5.0f;
    img.at(x, y, img.channelIndex("id")) = id;
    img.at(x, y, img.channelIndex("N.X")) = nx;
    img.at(x, y, img.channelIndex("N.Y")) = ny;
    img.at(x, y, img.channelIndex("N.Z")) = nz;
}

// Interior by its definition: every pixel of the disc (inside the image) is a same-body pixel
// of the centre's id.
Mask bruteForceInterior(const core::Image& ref, const Mask& sameBody, int r) {
    const int w = ref.width(), h = ref.height(), idC = ref.channelIndex("id");
    Mask m(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!sameBody(x, y)) continue;
            bool ok = true;
            for (int dy = -r; dy <= r && ok; ++dy)
                for (int dx = -r; dx <= r && ok; ++dx) {
                    const int qx = x + dx, qy = y + dy;
                    if (dx * dx + dy * dy > r * r || qx < 0 || qy < 0 || qx >= w || qy >= h)
                        continue;
                    ok = sameBody(qx, qy) && ref.at(qx, qy, idC) == ref.at(x, y, idC);
                }
            m.set(x, y, ok);
        }
    return m;
}

TEST(Masks, CoveredMeansAlphaAboveOneHalf) {
    core::Image img = core::aov::makeImage(3, 1);
    const int a = img.channelIndex("A");
    img.at(0, 0, a) = 0.5f;   // exactly half: not covered
    img.at(1, 0, a) = 0.51f;  // covered
    img.at(2, 0, a) = 1.0f;
    const Mask m = coveredMask(img);
    EXPECT_FALSE(m(0, 0));
    EXPECT_TRUE(m(1, 0));
    EXPECT_TRUE(m(2, 0));
    EXPECT_EQ(m.count(), 2u);
}

TEST(Masks, SameBodyNeedsCoverageInBothAndEqualIds) {
    core::Image ref = core::aov::makeImage(4, 1), test = core::aov::makeImage(4, 1);
    cover(ref, 0, 0, 1);  // covered in the reference only
    cover(ref, 1, 0, 1);
    cover(test, 1, 0, 1);  // same body
    cover(ref, 2, 0, 1);
    cover(test, 2, 0, 2);  // another body in front in the test
    cover(test, 3, 0, 3);  // covered in the test only
    const Masks m = computeMasks(ref, test);
    EXPECT_EQ(m.coveredInBoth.count(), 2u);
    EXPECT_TRUE(m.coveredInBoth(1, 0) && m.coveredInBoth(2, 0));
    EXPECT_EQ(m.sameBody.count(), 1u);
    EXPECT_TRUE(m.sameBody(1, 0));
}

TEST(Masks, InteriorOfARectangleShrinksByTheRadius) {
    // Body columns 5..24, rows 4..17 in a 30x22 image. A pixel at column x keeps its disc inside
    // the body only if x - r >= 5 and x + r <= 24 (the axis offsets reach farthest; diagonal
    // ones stay within them), so the interior is columns 5+r..24-r, rows 4+r..17-r.
    core::Image img = core::aov::makeImage(30, 22);
    for (int y = 4; y <= 17; ++y)
        for (int x = 5; x <= 24; ++x) cover(img, x, y, 0);
    for (int r : {0, 1, 2, 3}) {
        MaskSettings s;
        s.interiorRadius = r;
        const Masks m = computeMasks(img, img, s);
        for (int y = 0; y < 22; ++y)
            for (int x = 0; x < 30; ++x) {
                const bool expected = x >= 5 + r && x <= 24 - r && y >= 4 + r && y <= 17 - r;
                ASSERT_EQ(m.interior(x, y), expected) << "r " << r << " at " << x << "," << y;
            }
        EXPECT_EQ(m.interior.count(), static_cast<std::size_t>((20 - 2 * r) * (14 - 2 * r)));
    }
}

TEST(Masks, BodyBoundariesAreErodedButTheImageEdgeIsNot) {
    // The whole 40x10 image is covered: body 1 in columns 0..19, body 2 in 20..39. With radius
    // 2 the two columns each side of the boundary go (18, 19 | 20, 21); rows 0 and 9 at the
    // image edge stay.
    core::Image img = core::aov::makeImage(40, 10);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 40; ++x) cover(img, x, y, x < 20 ? 1.0f : 2.0f);
    const Masks m = computeMasks(img, img);
    EXPECT_EQ(m.sameBody.count(), 400u);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 40; ++x) ASSERT_EQ(m.interior(x, y), x < 18 || x > 21) << x << "," << y;
}

TEST(Masks, AHoleInTheTestErodesADiscAroundIt) {
    // Test uncovered at (15, 15) only: with radius 2 the pixels within distance 2 of it leave
    // the interior: 13 of them (1 + 4 at distance 1 + 4 at sqrt 2 + 4 at distance 2).
    core::Image ref = core::aov::makeImage(30, 30);
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 30; ++x) cover(ref, x, y, 0);
    core::Image test = ref;
    test.at(15, 15, test.channelIndex("A")) = 0.0f;
    const Masks m = computeMasks(ref, test);
    EXPECT_EQ(m.interior.count(), 900u - 13u);
    EXPECT_FALSE(m.interior(13, 15));
    EXPECT_FALSE(m.interior(16, 16));
    EXPECT_TRUE(m.interior(17, 16));  // distance sqrt 5 > 2
}

TEST(Masks, InteriorEqualsItsDefinitionOnRandomBodies) {
    // Random blobs of three bodies and holes; ids disagree in places. The fast path (distance
    // to label boundaries first) must give exactly the disc test everywhere.
    const int w = 61, h = 47;
    core::Image ref = core::aov::makeImage(w, h), test = core::aov::makeImage(w, h);
    std::uint32_t state = 31u;
    auto next = [&] {
        state = 1664525u * state + 1013904223u;
        return static_cast<double>(state >> 8) / 16777216.0;
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // Bands of bodies by a slanted coordinate plus sparse noise.
            const float id = static_cast<float>(((x + 2 * y) / 40) % 3);
            if (next() > 0.004) cover(ref, x, y, id);
            if (next() > 0.004) cover(test, x, y, next() < 0.004 ? id + 1 : id);
        }
    for (int r : {1, 2, 3, 5}) {
        MaskSettings s;
        s.interiorRadius = r;
        const Masks m = computeMasks(ref, test, s);
        EXPECT_EQ(m.interior, bruteForceInterior(ref, m.sameBody, r)) << "r " << r;
        EXPECT_GT(m.interior.count(), 0u) << "r " << r;
    }
}

TEST(Masks, FacingTheLightUsesTheReferenceNormalAgainstTheLightDirection) {
    // Light travelling along -z (toward the viewer's back): surfaces with N.Z > 0 face it.
    core::Image ref = core::aov::makeImage(3, 1), test = core::aov::makeImage(3, 1);
    cover(ref, 0, 0, 0, 0, 0, 1);
    cover(ref, 1, 0, 0, 0, 0, -1);
    cover(ref, 2, 0, 0, 1, 0, 0);  // grazing: N.L = 0 does not face it
    for (int x = 0; x < 3; ++x) cover(test, x, 0, 0, 0, 0, -1);  // the test's normals do not matter
    MaskSettings s;
    s.hasLight = true;
    s.lightDirection = {0.0, 0.0, -2.0};  // any length
    const Mask lit = computeMasks(ref, test, s).facingLight;
    EXPECT_TRUE(lit(0, 0));
    EXPECT_FALSE(lit(1, 0));
    EXPECT_FALSE(lit(2, 0));
    // Unknown light: every pixel covered in both.
    EXPECT_EQ(computeMasks(ref, test).facingLight.count(), 3u);
}

TEST(Masks, BadInput) {
    const core::Image a = core::aov::makeImage(8, 6), b = core::aov::makeImage(6, 8);
    EXPECT_THROW(computeMasks(a, b), core::NotComparableError);
    MaskSettings negative;
    negative.interiorRadius = -1;
    EXPECT_THROW(computeMasks(a, a, negative), std::invalid_argument);
    MaskSettings zeroLight;
    zeroLight.hasLight = true;
    zeroLight.lightDirection = {0.0, 0.0, 0.0};
    EXPECT_THROW(computeMasks(a, a, zeroLight), std::invalid_argument);
    const core::Image noA(8, 6, {"R", "G", "B"});
    try {
        coveredMask(noA);
        FAIL() << "expected NotComparableError";
    } catch (const core::NotComparableError& e) {
        EXPECT_NE(std::string(e.what()).find("\"A\""), std::string::npos) << e.what();
    }
}

TEST(Masks, ToImageIsOneChannelOfZerosAndOnes) {
    Mask m(3, 2);
    m.set(1, 1, true);
    const core::Image img = m.toImage("covered");
    ASSERT_EQ(img.channelNames(), std::vector<std::string>{"covered"});
    EXPECT_EQ(img.at(1, 1, 0), 1.0f);
    EXPECT_EQ(img.at(0, 0, 0), 0.0f);
}

}  // namespace
}  // namespace twinrender::compare
