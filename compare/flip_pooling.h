// Pooling of a ꟻLIP error map beyond its mean (beauty.flip): the 95th and 99th percentiles
// and the fraction of pixels whose error exceeds a level (beauty.flip_p95, beauty.flip_p99,
// beauty.flip_over). The mean hides rare large errors, a few pixels of a missing droplet or a
// shadow leak in a large image; these catch them, as Blender's render tests bound the share of
// pixels over a difference (-fail, -failpercent). NVlabs' ꟻLIP tool likewise reports the map's
// distribution (its weighted quartiles) beside the mean; pooling is a step apart from the
// metric (flip.h), over every pixel of the map, like the mean.
#pragma once

#include "core/image.h"

namespace twinrender::compare {

struct FlipPoolingSettings {
    // The ꟻLIP error a pixel must exceed to count in `over`, in (0, 1) (`--flip-over`). 0.5
    // is an error everyone sees when flipping between the images (the ꟻLIP map's upper half).
    double overLevel = 0.5;
};

struct FlipPooled {
    double p95 = 0.0;   // 95th percentile of the per-pixel error (numpy's linear method)
    double p99 = 0.0;   // 99th percentile
    double over = 0.0;  // fraction of the pixels whose error is above overLevel, in [0, 1]
};

// `errorMap`: one channel, the per-pixel ꟻLIP error (FlipResult::errorMap). NaN for all
// three when the map has no pixel. Throws std::invalid_argument when overLevel is not in
// (0, 1).
FlipPooled poolFlip(const core::Image& errorMap, const FlipPoolingSettings& settings = {});

}  // namespace twinrender::compare
