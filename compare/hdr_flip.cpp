#include "compare/hdr_flip.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "compare/flip.h"
#include "compare/image_pair.h"

namespace twinrender::compare {

namespace {

// ---- The paper's constants ---------------------------------------------------------------------

// The ACES tone mapper as a rational function per channel, (a x^2 + b x + c) / (d x^2 + e x + f)
// (Narkowicz 2015, times 0.6 to cancel its pre-exposure), as NVlabs' FLIP.h has it.
constexpr float TM_A = 0.6f * 0.6f * 2.51f, TM_B = 0.6f * 0.03f, TM_C = 0.0f;
constexpr float TM_D = 0.6f * 0.6f * 2.43f, TM_E = 0.6f * 0.59f, TM_F = 0.14f;
// The tone-mapped value that the brightest pixel (c_start) and the median one (c_stop) reach.
constexpr float t = 0.85f;

inline float toneMap(float x) {
    return (x * x * TM_A + x * TM_B + TM_C) / (x * x * TM_D + x * TM_E + TM_F);
}

inline float luminance(float r, float g, float b) {
    return 0.2126f * r + 0.7152f * g + 0.0722f * b;
}

// x_max: the radiance the tone mapper maps to t, the larger root of
// (a - t d) x^2 + (b - t e) x + (c - t f) = 0.
float radianceAtT() {
    const float a = TM_A - t * TM_D, b = TM_B - t * TM_E, c = TM_C - t * TM_F;
    const float d1 = -0.5f * (b / a);
    return d1 + std::sqrt(d1 * d1 - c / a);
}

// The reference and test exposed by 2^exposure, tone-mapped and clamped: linear RGB in [0, 1].
core::Image exposed(const float* rgb, int width, int height, float exposure) {
    core::Image out(width, height, {"R", "G", "B"});
    const float m = std::pow(2.0f, exposure);
    const auto pixels = out.pixels();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pixels.size()),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i)
                              pixels[i] = std::clamp(toneMap(rgb[i] * m), 0.0f, 1.0f);
                      });
    return out;
}

}  // namespace

ExposureRange exposureRange(double start, double stop) {
    if (!std::isfinite(start) || !std::isfinite(stop) || start > stop)
        throw std::invalid_argument(fmt::format(
            "beauty.hdrflip: the exposure range must be finite with start <= stop, got {} to {}",
            start, stop));
    // In float, as NVlabs' code counts them.
    const float span = static_cast<float>(stop) - static_cast<float>(start);
    return {start, stop, static_cast<int>(std::max(2.0f, std::ceil(span)))};
}

ExposureRange exposureRange(const core::Image& reference) {
    core::Image storage;
    const float* rgb = rgbPixels(reference, storage);
    std::vector<float> lit;
    float yMax = 0.0f;
    for (std::size_t p = 0; p < reference.pixelCount(); ++p) {
        const float y = luminance(rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]);
        if (!(y > 0.0f)) continue;  // black, negative or NaN: not in the median
        lit.push_back(y);
        yMax = std::max(yMax, y);
    }
    if (lit.empty()) return exposureRange(0.0, 0.0);
    // The upper median, as NVlabs' code takes it.
    const auto median = lit.begin() + static_cast<std::ptrdiff_t>(lit.size() / 2);
    std::nth_element(lit.begin(), median, lit.end());
    const float xMax = radianceAtT();
    return exposureRange(std::log2(xMax / yMax), std::log2(xMax / *median));
}

HdrFlipResult hdrFlip(const core::Image& reference, const core::Image& test,
                      const HdrFlipSettings& settings) {
    requireSameSize("beauty.hdrflip", reference, test);
    HdrFlipResult result;
    result.range = settings.range ? exposureRange(settings.range->start, settings.range->stop)
                                  : exposureRange(reference);
    if (settings.range && settings.range->count > 0)
        result.range.count = std::max(2, settings.range->count);
    const int width = reference.width(), height = reference.height();
    result.errorMap = core::Image(width, height, {"hdrflip"});
    if (reference.pixelCount() == 0) return result;
    core::Image refStorage, testStorage;
    const float* rgb[2] = {rgbPixels(reference, refStorage), rgbPixels(test, testStorage)};
    FlipSettings ldr;
    ldr.ppd = settings.ppd;
    ldr.input = FlipInput::Linear;
    // In float, as NVlabs' code steps through the exposures.
    const float start = static_cast<float>(result.range.start);
    const float step = (static_cast<float>(result.range.stop) - start) /
                       static_cast<float>(result.range.count - 1);
    const auto maxError = result.errorMap.pixels();
    for (int i = 0; i < result.range.count; ++i) {
        const float exposure = start + static_cast<float>(i) * step;
        const FlipResult f = flip(exposed(rgb[0], width, height, exposure),
                                  exposed(rgb[1], width, height, exposure), ldr);
        const auto error = f.errorMap.pixels();
        for (std::size_t p = 0; p < maxError.size(); ++p)
            maxError[p] = std::max(maxError[p], error[p]);
    }
    double total = 0.0;
    for (int y = 0; y < height; ++y) {
        double row = 0.0;  // by rows, as flip() sums its mean
        for (int x = 0; x < width; ++x) row += result.errorMap.at(x, y, 0);
        total += row;
    }
    result.mean = total / static_cast<double>(reference.pixelCount());
    return result;
}

}  // namespace twinrender::compare
