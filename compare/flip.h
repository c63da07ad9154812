// beauty.flip: LDR-FLIP, the perceptual difference an observer sees when flipping between the
// reference and the test image (docs/design.md, "Metrics").
//
// P. Andersson, J. Nilsson, T. Akenine-Moeller, M. Oskarsson, K. Astrom, M. D. Fairchild,
// "FLIP: A Difference Evaluator for Alternating Images", Proceedings of the ACM on Computer
// Graphics and Interactive Techniques (HPG 2020) 3(2), 15:1-15:23, doi:10.1145/3406183.
//
// Per pixel: both images go sRGB -> linear RGB -> YCxCz (opponent space), are filtered by the
// contrast sensitivity functions of the achromatic, red-green and blue-yellow channels
// (Gaussians with the paper's a1, b1, a2, b2), taken back to linear RGB (clamped), then to
// Hunt-adjusted L*a*b*; their HyAB distance, raised to qc and mapped so that pc * cmax lands
// at pt, is the colour error. Edges and points (first and second derivatives of a Gaussian
// whose width is set by w) detected in the achromatic channel of the unfiltered images give
// the feature difference, raised to qf. FLIP = colour error ^ (1 - feature difference).
// Outside the image every filter sees the nearest edge pixel. The filters are separable (the
// blue-yellow CSF as a sum of two separable Gaussians), as in NVlabs' reference code
// (github.com/NVlabs/flip, misc/separatedConvolutions.pdf); this is an independent
// implementation validated against it (flip_test.cpp).
#pragma once

#include "core/image.h"

namespace twinrender::compare {

// How the R, G, B values handed to flip() are encoded.
enum class FlipInput {
    Srgb,    // sRGB display values (a tonemapped image, a PNG): LDR-ꟻLIP
    Linear,  // linear values in [0, 1]: each tonemapped exposure of HDR-ꟻLIP (hdr_flip.h)
};

struct FlipSettings {
    // Observer's pixels per degree of visual angle, > 0. FLIP's default, 67, is a 0.7 m wide
    // 3840-pixel display seen from 0.7 m. Larger values hide finer detail.
    double ppd = 67.0;
    FlipInput input = FlipInput::Srgb;
};

struct FlipResult {
    double mean = 0.0;     // mean of errorMap over all pixels, in [0, 1]; 0 when identical
    core::Image errorMap;  // one channel "flip", the per-pixel FLIP error in [0, 1]
};

// reference and test: images with channels R, G, B holding sRGB display values in [0, 1] (the
// tonemapped image), or linear values in [0, 1] (settings.input). Values outside [0, 1] are
// clamped and NaN counts as 0, as the reference
// code does. Pooling other than the mean (percentiles, histograms) is a separate step on
// errorMap. Throws core::NotComparableError when the sizes differ (naming both) or a channel
// is missing; std::invalid_argument when ppd <= 0.
FlipResult flip(const core::Image& reference, const core::Image& test,
                const FlipSettings& settings = {});

}  // namespace twinrender::compare
