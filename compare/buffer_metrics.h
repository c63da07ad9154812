// The per-buffer metrics of docs/design.md ("Metrics"): how far the test's AOV buffers are from
// the reference's, each taken only over the mask where it means something (masks.h). Each is a
// pure function of (reference, test, masks) returning its value(s) and, where a pixel has an
// error of its own, a one-channel error map (0 outside the pixels named for it). Pooling is the
// mean unless said otherwise; a metric whose mask is empty is NaN, never a made-up number.
//
// Inputs are AOV images (core/frame.h, core::aov::channelNames()) of one size with masks from
// computeMasks on the same pair; a missing channel throws core::NotComparableError naming it.
// Sums are taken per row and added in row order: the results do not depend on the thread count.
#pragma once

#include <cstddef>
#include <vector>

#include "compare/masks.h"
#include "core/image.h"

namespace twinrender::compare {

// ---- coverage.iou -------------------------------------------------------------------------
// Jaccard index of the covered sets: |Cref n Ctest| / |Cref u Ctest|. 1 when neither image
// covers any pixel (they agree); NaN for an image of no pixels.
double coverageIou(const Masks& masks);

// ---- silhouette.mean_px -------------------------------------------------------------------
// An outline pixel is a covered pixel with a 4-neighbour inside the image that is not covered
// (the image edge is not an outline). The metric is the symmetric mean outline distance,
//   (sum_{a in Oref} d(a, Otest) + sum_{b in Otest} d(b, Oref)) / (|Oref| + |Otest|),
// d the Euclidean distance in pixels between pixel centres to the nearest pixel of the other
// outline (exact distance transform, distance_transform.h). 0 when the outlines coincide. NaN
// when neither image has an outline; +infinity when only one has (no outline to be near).
double silhouetteMeanPx(const Masks& masks);

// The outline pixels of a covered set, as defined above.
Mask outlineMask(const Mask& covered);

// ---- depth.rel_mean -----------------------------------------------------------------------
struct DepthResult {
    // Mean over same-body pixels (covered in both, same id) of |Ztest - Zref| / Zref (Z:
    // eye-space depth, scene units). Pixels whose visible body differs are occlusion errors
    // (id.mismatch), not depth errors. NaN when no pixel qualifies.
    double relMean = 0.0;
    core::Image errorMap;  // one channel "relative_error", on same-body pixels
};
DepthResult depthError(const core::Image& reference, const core::Image& test, const Masks& masks);

// ---- id.mismatch --------------------------------------------------------------------------
struct IdResult {
    // Fraction of covered-in-both pixels whose body id differs (occlusion-order errors), in
    // [0, 1]. NaN when no pixel is covered in both.
    double mismatch = 0.0;
    core::Image errorMap;  // one channel "mismatch": 1 where covered in both with different ids
};
IdResult idMismatch(const core::Image& reference, const core::Image& test, const Masks& masks);

// ---- normal.mean_deg, normal.p95_deg ------------------------------------------------------
// The angle between two normals, degrees in [0, 180]: atan2(|a x b|, a . b), which needs no
// normalisation and stays accurate for nearly parallel vectors (unlike acos of the dot
// product). A zero-length normal carries no direction: 90 degrees, the mean angle between a
// fixed and a random direction.
double angleDeg(double ax, double ay, double az, double bx, double by, double bz);

// The q-quantile (q in [0, 1]) of `values`, linear between order statistics (numpy's default
// "linear" method: position q (n - 1)). Reorders `values`. NaN when empty.
double quantile(std::vector<double>& values, double q);

struct NormalResult {
    double meanDeg = 0.0;  // mean angle over interior same-body pixels; NaN when there are none
    double p95Deg = 0.0;   // 95th percentile (quantile above) of the same angles; NaN when none
    // One channel "angle_deg": the angle wherever covered in both (the silhouette band
    // included, to show it; the pooled values use the interior only).
    core::Image errorMap;
};
NormalResult normalError(const core::Image& reference, const core::Image& test, const Masks& masks);

// ---- uv.mean ------------------------------------------------------------------------------
struct UvResult {
    // Mean over interior same-body pixels of sqrt(du^2 + dv^2), du = min(|dU|, 1 - |dU|) (u
    // wraps at the seam, u = 0.99 and 0.01 are 0.02 apart), dv = |dV|. NaN when no pixel.
    double mean = 0.0;
    core::Image errorMap;  // one channel "uv_error": that distance wherever covered in both
};
// The seam-aware uv distance used above.
double uvDistance(double uRef, double vRef, double uTest, double vTest);
UvResult uvError(const core::Image& reference, const core::Image& test, const Masks& masks);

// ---- emission.rmse ------------------------------------------------------------------------
struct EmissionResult {
    // Root of the mean over covered-in-both pixels and emission.R, .G, .B of the squared
    // difference, in emitted radiance units. NaN when no pixel is covered in both.
    double rmse = 0.0;
    // One channel "rmse": per pixel, the root of the mean over R, G, B of the squared difference.
    core::Image errorMap;
};
EmissionResult emissionError(const core::Image& reference, const core::Image& test,
                             const Masks& masks);

// ---- flux.ratio ---------------------------------------------------------------------------
// The light the test image holds over the reference's: the sum over every pixel of the linear
// beauty R + G + B of the test over the same sum of the reference. 1 when the two hold the same
// flux, below 1 when light is lost (a sub-pixel emitter whose impostor covers no pixel centre,
// realtime.particles.min_pixels). Summed over the whole image, so it measures one emitter on a
// black background honestly, not one among others. NaN when the reference's sum is 0.
double fluxRatio(const core::Image& reference, const core::Image& test);

// ---- smoothness.ratio ---------------------------------------------------------------------
struct SmoothnessResult {
    // testRoughnessDeg / referenceRoughnessDeg: 1 as smooth as the reference, > 1 rougher
    // (particle bumps the screen-space smoothing left), < 1 smoother (detail blurred away).
    // 1 when both roughnesses are 0 (two flat fields), +infinity when only the reference's is.
    // NaN when no pixel qualifies.
    double ratio = 0.0;
    // Roughness of a normal field, degrees: the mean over qualifying pixels of the mean angle
    // between the pixel's normal and its four 4-neighbours' normals. A pixel qualifies when it
    // and its four neighbours are all interior same-body pixels; both fields are measured on
    // the same pixels.
    double referenceRoughnessDeg = 0.0;
    double testRoughnessDeg = 0.0;
    std::size_t pixels = 0;  // qualifying pixels
};
SmoothnessResult smoothness(const core::Image& reference, const core::Image& test,
                            const Masks& masks);

// ---- shadow.iou, shadow.false_shadow, shadow.missed_shadow, shadow.mae, shadow.leak ---------
// A pixel is shadowed when its shadow channel (light visibility) is below this.
constexpr float SHADOWED_BELOW = 0.5f;

struct ShadowResult {
    // Over the pixels covered in both that face the light in the reference (masks.facingLight):
    // the Jaccard index of the shadowed sets (1 when neither image has a shadowed pixel there),
    double iou = 0.0;
    // the fraction of them lit in the reference and shadowed in the test (acne, over-biased
    // or too-dark shadow maps),
    double falseShadow = 0.0;
    // and the fraction shadowed in the reference and lit in the test (leaks, peter-panning).
    double missedShadow = 0.0;
    // The visibility itself (fractional under a sun with an angular radius, or a filtered map):
    // the mean of |test - reference| over those pixels,
    double mae = 0.0;
    // and the fraction of them lit in the test (visibility above SHADOWED_BELOW) where the
    // reference is in full shadow (visibility 0): light leaking into the umbra.
    // All five NaN when no pixel is covered in both and faces the light.
    double leak = 0.0;
    // One channel "disagreement": 1 false shadow, 2 missed shadow, 0 agreement or outside the
    // mask.
    core::Image errorMap;
};
// Codes of ShadowResult::errorMap.
constexpr float SHADOW_FALSE = 1.0f;
constexpr float SHADOW_MISSED = 2.0f;
ShadowResult shadowError(const core::Image& reference, const core::Image& test, const Masks& masks);

// ---- ao.mean_abs, ao.bias, ao.halo, ao.false, ao.missed -------------------------------------
// A reference pixel is on a depth edge when it is covered and a 4-neighbour in the image is
// not, shows another body, or lies deeper or shallower by more than this fraction of its depth:
// where a screen-space occlusion pass meets a depth discontinuity it cannot see behind.
constexpr double AO_DEPTH_EDGE = 0.05;
// The halo band: pixels within this many pixels (Euclidean) of a reference depth edge.
constexpr int AO_HALO_PX = 4;
// ao.false reads the pixels where the reference is open (at least this open fraction: within
// the traced truth's noise of 1 at 64 directions), ao.missed those where it is occluded (below
// this one).
constexpr double AO_OPEN = 0.99;
constexpr double AO_OCCLUDED = 0.9;

struct AoResult {
    // Over the pixels covered in both, of the ambient occlusion channel "ao" (the open fraction
    // of the cosine-weighted hemisphere within light.ao_radius): the mean of |test - reference|,
    double meanAbs = 0.0;
    // the mean of test - reference (positive: the test is too light, it misses occlusion;
    // negative: too dark, it invents occlusion),
    double bias = 0.0;
    // and the mean of |test - reference| over those within AO_HALO_PX of a reference depth
    // edge (NaN when there is none), where screen-space occlusion fails. NaN when no pixel is
    // covered in both.
    double halo = 0.0;
    // The error's texture on interior pixels (masks.interior): split into its local mean over
    // a window of AO_NOISE_WINDOW pixels a side (of the interior pixels in it) and the rest.
    // grain: the RMS of the rest, the noise finer than the window that a blur leaves;
    // banding: the RMS of the local mean about its own mean, the blotches and bands coarser
    // than the window (and any error that varies over the image). NaN without interior pixels.
    double grain = 0.0;
    double banding = 0.0;
    // Over the pixels covered in both where the reference is open (>= AO_OPEN): the mean of
    // max(reference - test, 0), the occlusion the test adds where there is none. NaN without
    // such pixels.
    double falseOcclusion = 0.0;
    // Over those where the reference is occluded (< AO_OCCLUDED): the share of its occlusion
    // (1 - reference) that the test leaves out, sum of clamp(test - reference, 0, 1 -
    // reference) over sum of (1 - reference); 0 all of it found (or more), 1 none (as no
    // occlusion). A method that trades false occlusion for missed shows in the pair. NaN
    // without such pixels.
    double missed = 0.0;
    core::Image errorMap;  // one channel "abs_error": |test - reference|, covered in both
};
// The window of ao.grain and ao.banding, pixels a side.
constexpr int AO_NOISE_WINDOW = 9;
// The reference's depth edges, as above.
Mask depthEdgeMask(const core::Image& reference, const Mask& referenceCovered);
AoResult aoError(const core::Image& reference, const core::Image& test, const Masks& masks);

// ---- indirect.rmse, indirect.missed, indirect.false -----------------------------------------

// A pixel is lit by emitting surfaces when the luminance of its irradiance (channels
// irradiance.R/G/B, light.emissive_light) is at least this fraction of the reference's 99th
// percentile over the pixels covered in both: light a person would see next to the brightest.
constexpr double INDIRECT_LIT_FRACTION = 0.05;

struct IndirectResult {
    // Over the pixels covered in both, of the irradiance's luminance (Rec. 709 weights): the
    // root mean square of test - reference, in the irradiance's units;
    double rmse = 0.0;
    // the fraction of the pixels lit in the reference that the test leaves dark (below the
    // threshold): emitters hidden from the screen, off it, or not sampled;
    double missed = 0.0;
    // the fraction of the pixels dark in the reference that the test lights: light through
    // occluders. NaN where the reference has no lit (missed) or no dark (false) pixel.
    double falseLight = 0.0;
    double threshold = 0.0;  // the luminance that counts as lit
    core::Image errorMap;    // one channel "abs_error": |test - reference| of the luminance
};
// Whether either image has irradiance anywhere (else the scene casts no such light and the
// metrics are left out).
bool hasIrradiance(const core::Image& reference, const core::Image& test);
IndirectResult indirectError(const core::Image& reference, const core::Image& test,
                             const Masks& masks);

// ---- inscatter.rmse, inscatter.rel ----------------------------------------------------------

struct InscatterResult {
    // Over the pixels where either frame has in-scatter (channels inscatter.R/G/B, a body's
    // atmosphere), covered or not, of its luminance (Rec. 709 weights): the root mean square of
    // test - reference, in radiance units;
    double rmse = 0.0;
    // that over the reference's root mean square on the same pixels (NaN where it is 0).
    double rel = 0.0;
    core::Image errorMap;  // one channel "abs_error": |test - reference| of the luminance
};
// Whether either image has in-scatter anywhere (else the scene has no atmosphere and the
// metrics are left out).
bool hasInscatter(const core::Image& reference, const core::Image& test);
InscatterResult inscatterError(const core::Image& reference, const core::Image& test);

}  // namespace twinrender::compare
