// beauty.psnr: peak signal-to-noise ratio of the tonemapped beauty image (docs/design.md,
// "Metrics"). PSNR = 10 log10(peak^2 / MSE), the MSE taken over all pixels and the R, G, B channels
// together, as scikit-image's peak_signal_noise_ratio(ref, test, data_range=1) does on an H x W x 3
// array. Reference: any signal-processing text; no paper constants.
#pragma once

#include <array>
#include <optional>

#include "core/image.h"

namespace twinrender::compare {

struct PsnrSettings {
    double peak = 1.0;      // largest possible display value, > 0; 1 for images in [0, 1]
    bool errorMap = false;  // also return the per-pixel squared error (mean over R, G, B)
};

struct PsnrResult {
    // dB. Identical images (MSE = 0) give +infinity: the ratio has no finite value, and a
    // report or JSON writer must map it (JSON has no infinity).
    double psnr = 0.0;
    double mse = 0.0;                     // mean over pixels and R, G, B, in display units^2
    std::array<double, 3> channelMse{};   // R, G, B
    std::optional<core::Image> errorMap;  // one channel "squared_error", when asked for
};

// reference and test: images with channels R, G, B holding display values (nominally [0, 1];
// values are used as given, not clamped). Other channels are ignored.
// Throws core::NotComparableError when the sizes differ (naming both) or a channel is missing.
PsnrResult psnr(const core::Image& reference, const core::Image& test,
                const PsnrSettings& settings = {});

}  // namespace twinrender::compare
