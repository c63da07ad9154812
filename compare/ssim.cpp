#include "compare/ssim.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "compare/image_pair.h"
#include "compare/row_kernel.h"
#include "core/error.h"

namespace twinrender::compare {

namespace {

// scipy.ndimage mode 'reflect' (half-sample symmetric): index -1 reads 0, -2 reads 1, n reads
// n - 1. Periodic, so any radius works on any size.
int reflectIndex(int i, int n) {
    const int period = 2 * n;
    i %= period;
    if (i < 0) i += period;
    return i < n ? i : period - 1 - i;
}

// scipy.ndimage.gaussian_filter1d's weights: exp(-x^2 / (2 sigma^2)) for |x| <= radius,
// normalised to sum 1.
std::vector<double> gaussianWindow(double sigma, int radius) {
    std::vector<double> g(2 * radius + 1);
    double sum = 0.0;
    for (int i = -radius; i <= radius; ++i) {
        g[i + radius] = std::exp(-0.5 * i * i / (sigma * sigma));
        sum += g[i + radius];
    }
    for (double& v : g) v /= sum;
    return g;
}

// The five local moments of a channel pair: E[x], E[y], E[x^2], E[y^2], E[xy]. They are
// filtered in double: in float, E[x^2] - E[x]^2 loses about 1e-7 to cancellation, which
// against C2 = 9e-4 moves SSIM by 1e-4 on flat regions.
constexpr int MOMENTS = 5;

// One tap of the filter along y, for all moments at once over n interleaved values of one
// row: m[j][i] += weight * (a, b, a^2, b^2, ab)[i].
TWINRENDER_ROW_KERNEL
void accumulateMoments(const float* __restrict a, const float* __restrict b, double weight,
                       std::size_t n, double* __restrict mx, double* __restrict my,
                       double* __restrict mxx, double* __restrict myy, double* __restrict mxy) {
    for (std::size_t i = 0; i < n; ++i) {
        const double ai = a[i], bi = b[i];
        mx[i] += weight * ai;
        my[i] += weight * bi;
        mxx[i] += weight * (ai * ai);
        myy[i] += weight * (bi * bi);
        mxy[i] += weight * (ai * bi);
    }
}

// The filter along x on an interleaved row of 3 values a pixel, padded by `radius` pixels on
// each side: out[i] = sum_k kernel[k] padded[i + 3 k], i in [0, n).
TWINRENDER_ROW_KERNEL
void convolveRgbRow(const double* __restrict padded, const double* __restrict kernel, int taps,
                    std::size_t n, double* __restrict out) {
    for (std::size_t i = 0; i < n; ++i) out[i] = 0.0;
    for (int k = 0; k < taps; ++k) {
        const double wk = kernel[k];
        const double* __restrict src = padded + 3 * static_cast<std::size_t>(k);
        for (std::size_t i = 0; i < n; ++i) out[i] += wk * src[i];
    }
}

// SSIM of each of n values from the filtered moments (Wang et al. 2004, eq. 13, with the
// variances and covariance as E[x^2] - E[x]^2 and E[xy] - E[x] E[y]).
TWINRENDER_ROW_KERNEL
void ssimRow(const double* __restrict ux, const double* __restrict uy, const double* __restrict uxx,
             const double* __restrict uyy, const double* __restrict uxy, double C1, double C2,
             std::size_t n, double* __restrict out) {
    for (std::size_t i = 0; i < n; ++i) {
        const double vx = uxx[i] - ux[i] * ux[i];
        const double vy = uyy[i] - uy[i] * uy[i];
        const double vxy = uxy[i] - ux[i] * uy[i];
        const double A1 = 2.0 * ux[i] * uy[i] + C1;
        const double A2 = 2.0 * vxy + C2;
        const double B1 = ux[i] * ux[i] + uy[i] * uy[i] + C1;
        const double B2 = vx + vy + C2;
        out[i] = (A1 * A2) / (B1 * B2);
    }
}

// One moment's row (3 values a pixel) padded by `radius` pixels on each side, mirrored as
// reflectIndex mirrors.
void padRow(const double* row, int w, int radius, double* padded) {
    std::copy(row, row + 3 * static_cast<std::size_t>(w), padded + 3 * radius);
    for (int x = -radius; x < 0; ++x)
        for (int c = 0; c < 3; ++c) padded[3 * (x + radius) + c] = row[3 * reflectIndex(x, w) + c];
    for (int x = w; x < w + radius; ++x)
        for (int c = 0; c < 3; ++c) padded[3 * (x + radius) + c] = row[3 * reflectIndex(x, w) + c];
}

}  // namespace

SsimResult ssim(const core::Image& reference, const core::Image& test,
                const SsimSettings& settings) {
    requireSameSize("beauty.ssim", reference, test);
    if (!(settings.sigma > 0.0) || !(settings.L > 0.0) || settings.K1 < 0.0 || settings.K2 < 0.0)
        throw std::invalid_argument(fmt::format(
            "beauty.ssim: need sigma > 0, L > 0, K1 >= 0, K2 >= 0; got sigma {}, L {}, K1 {}, "
            "K2 {}",
            settings.sigma, settings.L, settings.K1, settings.K2));
    const int w = reference.width();
    const int h = reference.height();
    // scikit-image: truncate = 3.5, radius as scipy rounds it; the cropped border is the same.
    const int radius = static_cast<int>(3.5 * settings.sigma + 0.5);
    const int winSize = 2 * radius + 1;
    if (w < winSize || h < winSize)
        throw core::NotComparableError(fmt::format(
            "beauty.ssim: the images are {}x{} pixels, smaller than the {}x{} Gaussian window "
            "(sigma {}); SSIM needs at least {}x{}",
            w, h, winSize, winSize, settings.sigma, winSize, winSize));
    core::Image refStorage, testStorage;
    const float* refRgb = rgbPixels(reference, refStorage);
    const float* testRgb = rgbPixels(test, testStorage);

    const std::vector<double> window = gaussianWindow(settings.sigma, radius);
    const double C1 = (settings.K1 * settings.L) * (settings.K1 * settings.L);
    const double C2 = (settings.K2 * settings.L) * (settings.K2 * settings.L);
    const int pad = (winSize - 1) / 2;  // border left out of the mean, as scikit-image crops
    const std::size_t rowValues = 3 * static_cast<std::size_t>(w);
    const std::size_t paddedValues = 3 * static_cast<std::size_t>(w + 2 * radius);

    SsimResult result;
    if (settings.ssimMap) result.ssimMap.emplace(w, h, std::vector<std::string>{"ssim"});
    core::Image* map = result.ssimMap ? &*result.ssimMap : nullptr;
    // Per-row sums of the SSIM map inside the cropped border, per channel; added up in row
    // order afterwards, so the result does not depend on the number of threads.
    std::vector<std::array<double, 3>> rowSums(static_cast<std::size_t>(h));

    // Each output row: filter the 2r + 1 input rows around it along y (all moments, R, G, B
    // interleaved), then along x, then SSIM. Separable filters commute, so this is the same
    // 2-D Gaussian scikit-image applies; nothing larger than a few rows is ever stored.
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        std::vector<double> vertical(MOMENTS * rowValues), filtered(MOMENTS * rowValues);
        std::vector<double> padded(paddedValues), values(rowValues);
        for (int y = rows.begin(); y != rows.end(); ++y) {
            std::fill(vertical.begin(), vertical.end(), 0.0);
            double* v[MOMENTS];
            for (int m = 0; m < MOMENTS; ++m) v[m] = &vertical[m * rowValues];
            for (int k = 0; k < winSize; ++k) {
                const std::size_t row = static_cast<std::size_t>(reflectIndex(y + k - radius, h));
                accumulateMoments(refRgb + row * rowValues, testRgb + row * rowValues, window[k],
                                  rowValues, v[0], v[1], v[2], v[3], v[4]);
            }
            for (int m = 0; m < MOMENTS; ++m) {
                padRow(v[m], w, radius, padded.data());
                convolveRgbRow(padded.data(), window.data(), winSize, rowValues,
                               &filtered[m * rowValues]);
            }
            ssimRow(&filtered[0 * rowValues], &filtered[1 * rowValues], &filtered[2 * rowValues],
                    &filtered[3 * rowValues], &filtered[4 * rowValues], C1, C2, rowValues,
                    values.data());
            // Summed in x order, per channel, inside the cropped border.
            std::array<double, 3> sums{};
            if (y >= pad && y < h - pad)
                for (int x = pad; x < w - pad; ++x)
                    for (int c = 0; c < 3; ++c)
                        sums[c] += values[3 * static_cast<std::size_t>(x) + c];
            if (map)
                for (int x = 0; x < w; ++x) {
                    double pixel = 0.0;
                    for (int c = 0; c < 3; ++c)
                        pixel += values[3 * static_cast<std::size_t>(x) + c];
                    map->at(x, y, 0) = static_cast<float>(pixel / 3.0);
                }
            rowSums[static_cast<std::size_t>(y)] = sums;
        }
    });

    const double count = static_cast<double>(w - 2 * pad) * static_cast<double>(h - 2 * pad);
    for (int c = 0; c < 3; ++c) {
        double total = 0.0;
        for (int y = pad; y < h - pad; ++y) total += rowSums[static_cast<std::size_t>(y)][c];
        result.channelSsim[c] = total / count;
    }
    result.ssim = (result.channelSsim[0] + result.channelSsim[1] + result.channelSsim[2]) / 3.0;
    return result;
}

}  // namespace twinrender::compare
