// beauty.ssim: structural similarity of the tonemapped beauty image (docs/design.md, "Metrics").
//
// Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image quality assessment: from error
// visibility to structural similarity", IEEE Transactions on Image Processing 13(4), 600-612,
// 2004. SSIM(x, y) = (2 mu_x mu_y + C1)(2 sigma_xy + C2) / ((mu_x^2 + mu_y^2 + C1)
// (sigma_x^2 + sigma_y^2 + C2)), C1 = (K1 L)^2, C2 = (K2 L)^2, with local statistics weighted
// by a circular Gaussian window (sigma 1.5, 11 x 11) and population (not sample) covariances.
//
// Computed per channel R, G, B and averaged, exactly as scikit-image 0.19's
// structural_similarity(ref, test, channel_axis=2, gaussian_weights=True, sigma=1.5,
// use_sample_covariance=False, data_range=1.0):
//  - the window is scipy's gaussian_filter with truncate 3.5: radius int(3.5 sigma + 0.5) = 5,
//    weights exp(-x^2 / (2 sigma^2)) normalised to sum 1, applied separably;
//  - outside the image the filter sees the image mirrored with the edge pixel repeated
//    (scipy mode 'reflect': d c b a | a b c d | d c b a);
//  - the mean skips a border of (window - 1) / 2 = 5 pixels on each side, where the window
//    hangs over the edge; the map still covers every pixel;
//  - local moments in double precision, as scikit-image computes on float64 images (agreement
//    to 1e-8 on the test pairs).
#pragma once

#include <array>
#include <optional>

#include "core/image.h"

namespace twinrender::compare {

struct SsimSettings {
    double sigma = 1.5;   // Gaussian window standard deviation, pixels, > 0 (radius 5 at 1.5)
    double K1 = 0.01;     // paper's K1, small positive constant
    double K2 = 0.03;     // paper's K2, small positive constant
    double L = 1.0;       // dynamic range of the values, > 0; 1 for display values in [0, 1]
    bool ssimMap = true;  // also return the per-pixel SSIM map
};

struct SsimResult {
    double ssim = 0.0;                    // mean over R, G, B of each channel's mean SSIM, <= 1
    std::array<double, 3> channelSsim{};  // R, G, B: mean of the map inside the cropped border
    // One channel "ssim", every pixel: the mean over R, G, B of the per-channel SSIM (1 where
    // the images agree; lower is worse). Present when settings.ssimMap.
    std::optional<core::Image> ssimMap;
};

// reference and test: images with channels R, G, B holding display values (used as given,
// not clamped). Throws core::NotComparableError when the sizes differ (naming both), a channel
// is missing, or the image is smaller than the window (11 x 11 pixels at sigma 1.5), as
// scikit-image refuses such images too.
SsimResult ssim(const core::Image& reference, const core::Image& test,
                const SsimSettings& settings = {});

}  // namespace twinrender::compare
