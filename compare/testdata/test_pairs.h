// Image pairs for the beauty-metric tests, generated deterministically (no stored images):
// the same pairs are written as PNGs by the test ReferencePairs.WriteForReferenceTools
// (psnr_test.cpp) for the independent reference tools, whose numbers the tests pin
// (compare/testdata/reference_values.py shows how they were produced). Every value is a
// multiple of 1/255, so the 8-bit PNGs hold exactly the pixels the tests see.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"

namespace twinrender::compare::testdata {

// Odd, non-square, larger than every filter window (SSIM 11, FLIP 21 at 67 ppd).
constexpr int WIDTH = 97;
constexpr int HEIGHT = 71;

// 32-bit linear congruential generator (Numerical Recipes' constants): the same sequence on
// every platform.
class Lcg {
  public:
    explicit Lcg(std::uint32_t seed) : mState(seed) {}
    // Uniform in [0, 1), 24 bits.
    float next() {
        mState = 1664525u * mState + 1013904223u;
        return static_cast<float>(mState >> 8) / 16777216.0f;
    }

  private:
    std::uint32_t mState;
};

inline float quantise(float v) {
    return std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f;
}

struct Rgb {
    float r, g, b;
};

template <typename F>
core::Image makeImage(int width, int height, F&& pixel) {
    core::Image image(width, height, {"R", "G", "B"});
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const Rgb c = pixel(x, y);
            image.at(x, y, 0) = quantise(c.r);
            image.at(x, y, 1) = quantise(c.g);
            image.at(x, y, 2) = quantise(c.b);
        }
    return image;
}

inline Rgb gradient(int x, int y) {
    const float u = static_cast<float>(x) / (WIDTH - 1);
    const float v = static_cast<float>(y) / (HEIGHT - 1);
    return {0.1f + 0.8f * u, 0.15f + 0.7f * v, 0.9f - 0.4f * u - 0.3f * v};
}

struct TestPair {
    std::string name;
    core::Image reference;
    core::Image test;
};

// 1. A smooth colour gradient against itself plus uniform noise of +-0.1 per channel.
inline TestPair gradientNoise() {
    Lcg lcg(12345u);
    core::Image ref = makeImage(WIDTH, HEIGHT, gradient);
    core::Image test = makeImage(WIDTH, HEIGHT, [&](int x, int y) {
        const Rgb c = gradient(x, y);
        const float nr = lcg.next(), ng = lcg.next(), nb = lcg.next();
        return Rgb{c.r + 0.2f * (nr - 0.5f), c.g + 0.2f * (ng - 0.5f), c.b + 0.2f * (nb - 0.5f)};
    });
    return {"gradient_noise", std::move(ref), std::move(test)};
}

// 2. An 8-pixel checkerboard of two colours against itself shifted by (2, 1) pixels: edges.
inline Rgb checker(int x, int y) {
    const bool odd = ((x / 8) + (y / 8)) % 2 != 0;
    return odd ? Rgb{0.9f, 0.8f, 0.2f} : Rgb{0.1f, 0.2f, 0.6f};
}
inline TestPair checkerShift() {
    return {"checker_shift", makeImage(WIDTH, HEIGHT, checker),
            makeImage(WIDTH, HEIGHT, [](int x, int y) { return checker(x + 2, y + 1); })};
}

// 3. A hard-edged disc against the same disc blurred by a 5x5 box (clamped at the border):
// the softened silhouettes that screen-space smoothing makes.
inline Rgb disc(int x, int y) {
    const float dx = x + 0.5f - 0.5f * WIDTH, dy = y + 0.5f - 0.5f * HEIGHT;
    return dx * dx + dy * dy < 22.0f * 22.0f ? Rgb{0.95f, 0.6f, 0.3f} : Rgb{0.05f, 0.05f, 0.1f};
}
inline TestPair discBlur() {
    core::Image ref = makeImage(WIDTH, HEIGHT, disc);
    core::Image test = makeImage(WIDTH, HEIGHT, [&](int x, int y) {
        Rgb sum{0, 0, 0};
        for (int j = -2; j <= 2; ++j)
            for (int i = -2; i <= 2; ++i) {
                const int xx = std::clamp(x + i, 0, WIDTH - 1),
                          yy = std::clamp(y + j, 0, HEIGHT - 1);
                sum.r += ref.at(xx, yy, 0);
                sum.g += ref.at(xx, yy, 1);
                sum.b += ref.at(xx, yy, 2);
            }
        return Rgb{sum.r / 25.0f, sum.g / 25.0f, sum.b / 25.0f};
    });
    return {"disc_blur", std::move(ref), std::move(test)};
}

// 4. The gradient against a hue-shifted copy (red and blue partly exchanged): colour only.
inline TestPair colourShift() {
    return {"colour_shift", makeImage(WIDTH, HEIGHT, gradient),
            makeImage(WIDTH, HEIGHT, [](int x, int y) {
                const Rgb c = gradient(x, y);
                return Rgb{0.7f * c.r + 0.3f * c.b, c.g, 0.7f * c.b + 0.3f * c.r};
            })};
}

// 5. Near-black noise against different near-black noise (values 0..12 / 255): the linear
// segment of the sRGB curve and the linear branch of L*a*b*.
inline TestPair darkNoise() {
    Lcg lcg(777u);
    auto dark = [&](int, int) {
        return Rgb{std::floor(13.0f * lcg.next()) / 255.0f, std::floor(13.0f * lcg.next()) / 255.0f,
                   std::floor(13.0f * lcg.next()) / 255.0f};
    };
    core::Image ref = makeImage(WIDTH, HEIGHT, dark);
    core::Image test = makeImage(WIDTH, HEIGHT, dark);
    return {"dark_noise", std::move(ref), std::move(test)};
}

// 6. Uniform black against uniform white: the largest colour difference, no features.
inline TestPair blackWhite() {
    return {"black_white",
            makeImage(WIDTH, HEIGHT,
                      [](int, int) {
                          return Rgb{0, 0, 0};
                      }),
            makeImage(WIDTH, HEIGHT, [](int, int) {
                return Rgb{1, 1, 1};
            })};
}

// The same pixels with R, G, B stored in another order among other channels, as in an AOV
// image: metrics must read the channels by name.
inline core::Image withOtherChannels(const core::Image& rgb) {
    core::Image out(rgb.width(), rgb.height(), {"Z", "B", "A", "G", "R"});
    for (std::size_t p = 0; p < out.pixelCount(); ++p) {
        out.at(p, 0) = 7.0f;
        out.at(p, 1) = rgb.at(p, 2);
        out.at(p, 2) = 1.0f;
        out.at(p, 3) = rgb.at(p, 1);
        out.at(p, 4) = rgb.at(p, 0);
    }
    return out;
}

inline std::vector<TestPair> referencePairs() {
    std::vector<TestPair> pairs;
    pairs.push_back(gradientNoise());
    pairs.push_back(checkerShift());
    pairs.push_back(discBlur());
    pairs.push_back(colourShift());
    pairs.push_back(darkNoise());
    pairs.push_back(blackWhite());
    return pairs;
}

inline TestPair referencePair(const std::string& name) {
    for (auto& p : referencePairs())
        if (p.name == name) return p;
    return {};
}

}  // namespace twinrender::compare::testdata
