// Temporal error against the truth (docs/design.md, "Sequences"): what the real-time sequence
// changes from one frame to the next that the reference does not. Motion the truth has changes
// both alike and is not counted; what only the real-time renders change (particles that pop,
// smoothing that follows the particles' order rather than the surface) is flicker.
//
// Per consecutive frame pair: the mean ꟻLIP between the two real-time frames minus that
// between the two reference frames (temporal.flicker), and the mean angle between a pixel's
// normals in the two frames, over the pixels covered in both frames of both renders, real-time
// minus reference (temporal.normal_flicker_deg).
#pragma once

#include <cstddef>

#include "compare/flip.h"
#include "compare/thresholds.h"
#include "core/image.h"

namespace twinrender::compare {

// One frame of one renderer: its AOV image (normals, coverage) and its display image (ꟻLIP).
struct FrameImages {
    const core::Image& aov;
    const core::Image& display;
};

struct FrameChange {
    double realtimeFlip = 0.0;       // mean ꟻLIP between the two real-time frames
    double referenceFlip = 0.0;      // the same for the reference
    double realtimeNormalDeg = 0.0;  // mean normal change, degrees; NaN without common pixels
    double referenceNormalDeg = 0.0;
    std::size_t normalPixels = 0;  // covered in both frames of both renders

    double flicker() const { return realtimeFlip - referenceFlip; }
    double normalFlickerDeg() const { return realtimeNormalDeg - referenceNormalDeg; }
};

// The change from the previous frame to this one, for both renderers. The AOV images need the
// channels A and N.X, N.Y, N.Z (images without them give no normal change: NaN); every image
// must have the same size (core::NotComparableError otherwise).
FrameChange frameChange(const FrameImages& previousReference, const FrameImages& reference,
                        const FrameImages& previousTest, const FrameImages& test,
                        const FlipSettings& flip);

// The change as metrics: temporal.frame_flip, temporal.reference_frame_flip, temporal.flicker,
// temporal.normal_change_deg, temporal.reference_normal_change_deg,
// temporal.normal_flicker_deg.
void addFrameChangeMetrics(const FrameChange& change, MetricValues& metrics);

}  // namespace twinrender::compare
