// Bleeding across the contact of two bodies: the uv and emission errors on the pixels near the
// boundary between two bodies in the reference, where a screen-space filter that mixes pixels
// of different bodies (or a renderer that blends their attributes) shows first. The same
// errors over the whole interior (uv.mean) dilute it: a contact is a thin line.
#pragma once

#include <cstddef>

#include "compare/masks.h"
#include "core/image.h"

namespace twinrender::compare {

// Same-body pixels (masks.sameBody) with a pixel of another body, covered in the reference,
// within `radius` pixels (Euclidean, |offset| <= radius; offsets outside the image ignored).
// Throws std::invalid_argument for radius < 1.
Mask contactBandMask(const core::Image& reference, const Masks& masks, int radius);

struct ContactBandResult {
    // Over the band: the mean seam-aware uv distance (buffer_metrics.h's uvDistance) and the
    // root of the mean over pixels and emission.R, .G, .B of the squared difference. NaN when
    // the band is empty (no two bodies touch or overlap on screen).
    double uvMean = 0.0;
    double emissionRmse = 0.0;
    std::size_t pixels = 0;  // pixels in the band
};
ContactBandResult contactBandError(const core::Image& reference, const core::Image& test,
                                   const Masks& masks, int radius);

}  // namespace twinrender::compare
