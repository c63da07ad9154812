// Cost of the beauty metrics (compare/psnr, ssim, flip) on a 1920x1080 pair. The aim is
// the three together under 1 s on a 2-core machine. Run:
//   build/bench/metrics_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// and read the medians. Wall time (UseRealTime): the metrics run on all cores through oneTBB.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "bench/render_like_pair.h"
#include "compare/flip.h"
#include "compare/metrics.h"
#include "compare/psnr.h"
#include "compare/ssim.h"
#include "core/frame.h"

namespace twinrender::compare {
namespace {

const Pair& pair() {
    static const Pair p;
    return p;
}

void BM_Psnr(benchmark::State& state) {
    const Pair& p = pair();
    for (auto _ : state) benchmark::DoNotOptimize(psnr(p.reference, p.test).psnr);
}

void BM_Ssim(benchmark::State& state) {
    const Pair& p = pair();
    for (auto _ : state) benchmark::DoNotOptimize(ssim(p.reference, p.test).ssim);
}

void BM_Flip(benchmark::State& state) {
    const Pair& p = pair();
    for (auto _ : state) benchmark::DoNotOptimize(flip(p.reference, p.test).mean);
}

// What `twinrender compare` pays for the beauty metrics: all three, maps included.
void BM_AllBeautyMetrics(benchmark::State& state) {
    const Pair& p = pair();
    PsnrSettings withMap;
    withMap.errorMap = true;
    for (auto _ : state) {
        benchmark::DoNotOptimize(psnr(p.reference, p.test, withMap).psnr);
        benchmark::DoNotOptimize(ssim(p.reference, p.test).ssim);
        benchmark::DoNotOptimize(flip(p.reference, p.test).mean);
    }
}

// A render-like AOV pair for computeMetrics: two overlapping spheres (radii 400 and 250
// pixels, bodies 0 and 1) with sphere normals, lat-long uv, depth, a shadowed patch and glow
// on body 1; the test shifted 2 pixels right with noisy normals, as an unsmoothed impostor
// render would be.
struct AovPair {
    core::Image reference = make(0, 0.0f);
    core::Image test = make(2, 0.05f);

    static core::Image make(int shift, float noise) {
        core::Image img = core::aov::makeImage(WIDTH, HEIGHT);
        int c[15];
        for (int i = 0; i < 15; ++i) c[i] = img.channelIndex(core::aov::channelNames()[i]);
        std::uint32_t state = 7u;
        auto next = [&] {
            state = 1664525u * state + 1013904223u;
            return static_cast<float>(state >> 8) / 16777216.0f - 0.5f;
        };
        const float spheres[2][4] = {{860.0f, 540.0f, 400.0f, 30.0f},
                                     {1250.0f, 600.0f, 250.0f, 20.0f}};
        for (int y = 0; y < HEIGHT; ++y)
            for (int x = 0; x < WIDTH; ++x)
                for (int b = 1; b >= 0; --b) {
                    const float* s = spheres[b];
                    const float dx = (x + 0.5f - shift - s[0]) / s[2];
                    const float dy = -(y + 0.5f - s[1]) / s[2];
                    const float d2 = dx * dx + dy * dy;
                    if (d2 >= 1.0f) continue;
                    float n[3] = {dx + noise * next(), dy + noise * next(),
                                  std::sqrt(1.0f - d2) + noise * next()};
                    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                    for (float& v : n) v /= len;
                    const float lit = (b == 0 && dx > 0.2f && dy > 0.1f) ? 0.0f : 1.0f;
                    const float diffuse =
                        std::max(0.0f, -0.5f * n[0] + 0.6f * n[1] + 0.6f * n[2]) * lit;
                    const float glow = b == 1 ? 0.3f : 0.0f;
                    const float values[15] = {
                        0.8f * diffuse + glow,
                        0.6f * diffuse,
                        0.4f * diffuse,
                        1.0f,
                        s[3] - s[2] * 0.01f * n[2],
                        n[0],
                        n[1],
                        n[2],
                        std::atan2(n[0], n[2]) / (2.0f * std::numbers::pi_v<float>)+0.5f,
                        0.5f + std::asin(n[1]) / std::numbers::pi_v<float>,
                        static_cast<float>(b),
                        glow,
                        0.5f * glow,
                        0.0f,
                        lit};
                    for (int i = 0; i < 15; ++i) img.at(x, y, c[i]) = values[i];
                    break;
                }
        return img;
    }
};

// What `twinrender compare` pays for two AOV EXRs: every metric (the three beauty metrics on
// the tonemapped beauty, the masks, every per-buffer metric and all error maps). The aim:
// under 1 s on a 2-core machine.
void BM_AllMetrics1080p(benchmark::State& state) {
    static const AovPair p;
    MetricSettings settings;
    settings.hasLight = true;
    settings.lightDirection = {0.5, -0.6, -0.6};
    for (auto _ : state)
        benchmark::DoNotOptimize(computeMetrics(p.reference, p.test, settings).values);
}

BENCHMARK(BM_Psnr)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Ssim)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Flip)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AllBeautyMetrics)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AllMetrics1080p)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace twinrender::compare

BENCHMARK_MAIN();
