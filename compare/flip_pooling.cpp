#include "compare/flip_pooling.h"

#include <fmt/format.h>

#include <limits>
#include <stdexcept>
#include <vector>

#include "compare/buffer_metrics.h"

namespace twinrender::compare {

namespace {

constexpr double P95 = 0.95;  // beauty.flip_p95
constexpr double P99 = 0.99;  // beauty.flip_p99

}  // namespace

FlipPooled poolFlip(const core::Image& errorMap, const FlipPoolingSettings& settings) {
    if (!(settings.overLevel > 0.0 && settings.overLevel < 1.0))
        throw std::invalid_argument(fmt::format(
            "ꟻLIP pooling: the error level must be in (0, 1), got {}", settings.overLevel));
    if (errorMap.channelCount() != 1)
        throw std::invalid_argument(
            fmt::format("ꟻLIP pooling: the error map must have one channel, it has {}",
                        errorMap.channelCount()));
    const auto pixels = errorMap.pixels();
    FlipPooled pooled;
    if (pixels.empty()) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        return {nan, nan, nan};
    }
    std::vector<double> values;
    core::reserveHugePages(values, pixels.size());
    values.assign(pixels.begin(), pixels.end());
    std::size_t over = 0;
    for (double v : values) over += v > settings.overLevel;
    pooled.over = static_cast<double>(over) / static_cast<double>(values.size());
    // The 99th percentile first: its partition leaves the 95th's order statistics in the lower
    // part, which quantile then reorders less.
    pooled.p99 = quantile(values, P99);
    pooled.p95 = quantile(values, P95);
    return pooled;
}

}  // namespace twinrender::compare
