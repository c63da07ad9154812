// beauty.hdrflip: HDR-ꟻLIP, the error an observer sees when flipping between two linear
// (high dynamic range) images over the exposures a viewer might choose.
//
// P. Andersson, J. Nilsson, P. Shirley, T. Akenine-Moeller, "Visualizing Errors in Rendered
// High Dynamic Range Images", Eurographics 2021 Short Papers, doi:10.2312/egs.20211015.
//
// Both images are exposed at n exposures c evenly spaced from c_start to c_stop (radiance
// times 2^c), tonemapped with the ACES curve the paper uses (Narkowicz's fit with the 0.6
// pre-exposure cancelled, as in NVlabs' code), clamped to [0, 1] and compared by LDR-ꟻLIP
// (flip.h) on those linear values; a pixel's HDR-ꟻLIP error is its largest LDR-ꟻLIP error over
// the exposures, the mean over every pixel the metric.
//
// The exposure range comes from the reference (the paper's Section 3): c_start =
// log2(x_max / Y_max) exposes its brightest pixel to the tone mapper's 0.85, c_stop =
// log2(x_max / Y_median) its median pixel, n = max(2, ceil(c_stop - c_start)), where x_max is
// the radiance the tone mapper maps to 0.85 and Y the luminance (Rec. 709 weights). One change:
// Y_median is the median of the pixels whose luminance is above 0. Over every pixel, as NVlabs'
// tool takes it, the median of particles on black space is 0 and c_stop infinite. An all-black
// reference gives c_start = c_stop = 0.
#pragma once

#include <optional>

#include "core/image.h"

namespace twinrender::compare {

// Exposures in stops: c_start <= c_stop, count >= 2 (the paper's n). In HdrFlipSettings,
// count 0 asks for the paper's, max(2, ceil(stop - start)).
struct ExposureRange {
    double start = 0.0;
    double stop = 0.0;
    int count = 0;
};

// The range of `reference` (linear R, G, B) as above.
ExposureRange exposureRange(const core::Image& reference);

// A range between start and stop (start <= stop) with the paper's count, max(2,
// ceil(stop - start)); throws std::invalid_argument for start > stop or non-finite values.
ExposureRange exposureRange(double start, double stop);

struct HdrFlipSettings {
    double ppd = 67.0;  // as FlipSettings::ppd
    // An explicit range (as NVlabs' tool takes -cstart, -cstop, -n); nullopt:
    // exposureRange(reference).
    std::optional<ExposureRange> range;
};

struct HdrFlipResult {
    double mean = 0.0;     // mean of errorMap over all pixels, in [0, 1]
    core::Image errorMap;  // one channel "hdrflip": the largest LDR-ꟻLIP error per pixel
    ExposureRange range;   // the exposures used
};

// reference and test: linear R, G, B (any non-negative radiance). Throws as flip() does for
// sizes and channels; std::invalid_argument for a bad ppd or range.
HdrFlipResult hdrFlip(const core::Image& reference, const core::Image& test,
                      const HdrFlipSettings& settings = {});

}  // namespace twinrender::compare
