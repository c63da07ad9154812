#include "realtime/frame_assembly.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <utility>
#include <vector>

#include "core/frame.h"
#include "realtime/octahedral.h"

namespace twinrender::realtime {
namespace {

// A 3 x 2 read-back, every pixel on the background except GL pixel (2, 0): the bottom row's
// last pixel, the image's (2, 1). Display values tell the pixels apart.
struct ReadBack {
    static constexpr int W = 3, H = 2;
    const glm::vec3 normal = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
    std::vector<float> normalUv, emission, surface, beautyShadow, display;

    ReadBack()
        : normalUv(W * H * 4, 0.0f),
          emission(W * H * 4, 0.0f),
          surface(W * H * 4, 0.0f),
          beautyShadow(W * H * 4, 0.0f),
          display(W * H * 4, 1.0f) {
        for (int p = 0; p < W * H; ++p) {
            surface[p * 4 + 0] = INFINITY;
            surface[p * 4 + 1] = -1.0f;
            for (int k = 0; k < 3; ++k) display[p * 4 + k] = 0.1f * p + 0.01f * k;
        }
        const int g = 2 * 4;  // GL pixel (2, 0)
        const glm::vec2 e = octEncode(normal);
        normalUv[g + 0] = e.x;
        normalUv[g + 1] = e.y;
        normalUv[g + 2] = 0.25f;
        normalUv[g + 3] = 0.75f;
        for (int k = 0; k < 3; ++k) emission[g + k] = 0.5f + k;
        surface[g + 0] = 4.5f;  // eye depth
        surface[g + 1] = 3.0f;  // body
        beautyShadow[g + 0] = 0.2f;
        beautyShadow[g + 1] = 0.3f;
        beautyShadow[g + 2] = 0.4f;
        beautyShadow[g + 3] = 0.0f;  // in shadow
    }

    ReadBackBuffers buffers(bool emits) const {
        ReadBackBuffers b;
        b.width = W;
        b.height = H;
        b.normalUv = normalUv;
        if (emits) b.emission = emission;
        b.surface = surface;
        b.beautyShadow = beautyShadow;
        b.display = display;
        return b;
    }
};

// Images holding an older frame's values everywhere, as recycled ones do.
core::Image staleAov() {
    core::Image image(ReadBack::W, ReadBack::H, core::aov::channelNames());
    for (float& v : image.pixels()) v = 7.0f;
    return image;
}

float channel(const core::Image& image, int x, int y, const char* name) {
    return image.at(x, y, image.requireChannel(name));
}

TEST(FrameAssembly, CoveredPixelTakesEveryBufferRowsFlipped) {
    const ReadBack rb;
    core::Image aov = staleAov(), display(ReadBack::W, ReadBack::H, {"R", "G", "B"});
    assembleFrame(rb.buffers(true), aov, display);
    // GL's bottom row is the image's last.
    const int x = 2, y = 1;
    const std::pair<const char*, float> expected[] = {
        {"R", 0.2f},     {"G", 0.3f},          {"B", 0.4f},          {"A", 1.0f},
        {"Z", 4.5f},     {"id", 3.0f},         {"shadow", 0.0f},     {"uv.U", 0.25f},
        {"uv.V", 0.75f}, {"emission.R", 0.5f}, {"emission.G", 1.5f}, {"emission.B", 2.5f}};
    for (const auto& [name, value] : expected) EXPECT_EQ(channel(aov, x, y, name), value) << name;
    const glm::vec3 n(channel(aov, x, y, "N.X"), channel(aov, x, y, "N.Y"),
                      channel(aov, x, y, "N.Z"));
    EXPECT_GT(glm::dot(n, rb.normal), 1.0f - 1e-6f);
    // Display: image row y is GL row H - 1 - y.
    for (int py = 0; py < ReadBack::H; ++py)
        for (int px = 0; px < ReadBack::W; ++px)
            for (int k = 0; k < 3; ++k)
                EXPECT_EQ(display.at(px, py, k),
                          rb.display[((ReadBack::H - 1 - py) * ReadBack::W + px) * 4 + k]);
}

TEST(FrameAssembly, BackgroundOverwritesAnOlderFrame) {
    const ReadBack rb;
    core::Image aov = staleAov(), display(ReadBack::W, ReadBack::H, {"R", "G", "B"});
    assembleFrame(rb.buffers(true), aov, display);
    const core::Image background = core::aov::makeImage(1, 1);
    for (int y = 0; y < ReadBack::H; ++y)
        for (int x = 0; x < ReadBack::W; ++x) {
            if (x == 2 && y == 1) continue;
            for (int c = 0; c < background.channelCount(); ++c)
                EXPECT_EQ(aov.at(x, y, c), background.at(0, 0, c))
                    << x << "," << y << " " << background.channelNames()[c];
        }
}

TEST(FrameAssembly, ABackgroundPixelKeepsTheLightOfAHalo) {
    ReadBack rb;
    // GL pixel (0, 0), on the background: a sub-pixel emitter's halo lit it.
    rb.beautyShadow[0] = 0.125f;
    rb.beautyShadow[1] = 0.25f;
    rb.beautyShadow[2] = 0.5f;
    core::Image aov = staleAov(), display(ReadBack::W, ReadBack::H, {"R", "G", "B"});
    assembleFrame(rb.buffers(true), aov, display);
    const int y = ReadBack::H - 1;  // GL's bottom row
    EXPECT_EQ(channel(aov, 0, y, "R"), 0.125f);
    EXPECT_EQ(channel(aov, 0, y, "G"), 0.25f);
    EXPECT_EQ(channel(aov, 0, y, "B"), 0.5f);
    // Still the background in every other channel.
    EXPECT_EQ(channel(aov, 0, y, "A"), 0.0f);
    EXPECT_EQ(channel(aov, 0, y, "id"), -1.0f);
    EXPECT_TRUE(std::isinf(channel(aov, 0, y, "Z")));
}

TEST(FrameAssembly, WithoutEmittersTheEmissionIsZero) {
    const ReadBack rb;  // its emission buffer holds values, as a stale read-back buffer can
    core::Image aov = staleAov(), display(ReadBack::W, ReadBack::H, {"R", "G", "B"});
    assembleFrame(rb.buffers(false), aov, display);
    for (const char* c : {"emission.R", "emission.G", "emission.B"})
        EXPECT_EQ(channel(aov, 2, 1, c), 0.0f) << c;
    EXPECT_EQ(channel(aov, 2, 1, "R"), 0.2f);
}

}  // namespace
}  // namespace twinrender::realtime
