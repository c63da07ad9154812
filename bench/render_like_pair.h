// The render-like 1920x1080 pair the beauty-metric benchmarks compare (metrics_bench, and
// compare_process_bench as PNGs).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/image.h"

namespace twinrender::compare {

constexpr int WIDTH = 1920;
constexpr int HEIGHT = 1080;

// A render-like pair: a gradient sky, a large lit disc, and in the test a softened,
// slightly shifted disc edge plus a little noise (fixed-seed LCG).
struct Pair {
    core::Image reference{WIDTH, HEIGHT, {"R", "G", "B"}};
    core::Image test{WIDTH, HEIGHT, {"R", "G", "B"}};

    Pair() {
        std::uint32_t state = 2024u;
        auto noise = [&] {
            state = 1664525u * state + 1013904223u;
            return static_cast<float>(state >> 8) / 16777216.0f - 0.5f;
        };
        for (int y = 0; y < HEIGHT; ++y)
            for (int x = 0; x < WIDTH; ++x) {
                const float sky[3] = {0.2f + 0.3f * y / HEIGHT, 0.3f + 0.2f * x / WIDTH, 0.6f};
                const float dx = x - 960.0f, dy = y - 540.0f;
                const float r = std::sqrt(dx * dx + dy * dy);
                const float inRef = r < 400.0f ? 1.0f : 0.0f;
                const float inTest = std::clamp((402.0f - r) / 4.0f, 0.0f, 1.0f);
                const float lit = 0.5f + 0.4f * dx / 400.0f;
                const float body[3] = {0.9f * lit, 0.7f * lit, 0.4f * lit};
                for (int c = 0; c < 3; ++c) {
                    reference.at(x, y, c) = inRef * body[c] + (1 - inRef) * sky[c];
                    test.at(x, y, c) = std::clamp(
                        inTest * body[c] + (1 - inTest) * sky[c] + 0.02f * noise(), 0.0f, 1.0f);
                }
            }
    }
};

}  // namespace twinrender::compare
