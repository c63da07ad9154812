#include "compare/psnr.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "compare/image_pair.h"
#include "core/error.h"

namespace twinrender::compare {

namespace {}  // namespace

PsnrResult psnr(const core::Image& reference, const core::Image& test,
                const PsnrSettings& settings) {
    requireSameSize("beauty.psnr", reference, test);
    if (!(settings.peak > 0.0))
        throw std::invalid_argument(
            fmt::format("beauty.psnr: peak must be > 0, got {}", settings.peak));
    const int refC[3] = {reference.requireChannel("R"), reference.requireChannel("G"),
                         reference.requireChannel("B")};
    const int testC[3] = {test.requireChannel("R"), test.requireChannel("G"),
                          test.requireChannel("B")};
    const int w = reference.width();
    const int h = reference.height();

    PsnrResult result;
    if (settings.errorMap) result.errorMap.emplace(w, h, std::vector<std::string>{"squared_error"});
    core::Image* map = result.errorMap ? &*result.errorMap : nullptr;

    // Per-row sums, added up in row order afterwards: the result is the same for any number
    // of threads.
    std::vector<std::array<double, 3>> rowSums(static_cast<std::size_t>(h));
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y) {
            std::array<double, 3> sum{};
            for (int x = 0; x < w; ++x) {
                double pixel = 0.0;
                for (int c = 0; c < 3; ++c) {
                    const double d = static_cast<double>(reference.at(x, y, refC[c])) -
                                     static_cast<double>(test.at(x, y, testC[c]));
                    sum[c] += d * d;
                    pixel += d * d;
                }
                if (map) map->at(x, y, 0) = static_cast<float>(pixel / 3.0);
            }
            rowSums[static_cast<std::size_t>(y)] = sum;
        }
    });

    std::array<double, 3> total{};
    for (const auto& row : rowSums)
        for (int c = 0; c < 3; ++c) total[c] += row[c];
    const double n = static_cast<double>(reference.pixelCount());
    for (int c = 0; c < 3; ++c) result.channelMse[c] = n > 0 ? total[c] / n : 0.0;
    result.mse = n > 0 ? (total[0] + total[1] + total[2]) / (3.0 * n) : 0.0;
    result.psnr = result.mse > 0.0 ? 10.0 * std::log10(settings.peak * settings.peak / result.mse)
                                   : std::numeric_limits<double>::infinity();
    return result;
}

}  // namespace twinrender::compare
