// Every metric of a pair of frames, by the names of docs/design.md ("Metrics"): the one call
// `twinrender compare` and `run` make.
//
// Two AOV images (channels of core::aov::channelNames(): R, G, B and any of the others): the
// beauty metrics on the tonemapped sRGB beauty (the image a person sees), beauty.hdrflip on the
// linear beauty, and every per-buffer metric whose channels both images carry, over its mask
// (masks.h, buffer_metrics.h); the others are "not provided" (MetricResult::notProvided), never
// 0 and never a pass. Two plain images (no AOV channel other than R, G, B, A; e.g. PNGs): the
// beauty metrics only, on R, G, B as given.
#pragma once

#include <glm/vec3.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "compare/flip_pooling.h"
#include "compare/hdr_flip.h"
#include "compare/masks.h"
#include "core/image.h"

namespace twinrender::compare {

struct MetricSettings {
    // FLIP observer's pixels per degree (`--ppd`), > 0; 67 is FLIP's default.
    double ppd = 67.0;
    // The ꟻLIP error above which a pixel counts in beauty.flip_over (`--flip-over`), in
    // (0, 1); flip_pooling.h.
    double flipOver = FlipPoolingSettings{}.overLevel;
    // Multiplies the linear beauty before the tonemapper (core::tonemap), > 0. AOV images only.
    double exposure = 1.0;
    // The way the light travels (the scene's light.direction, core::LightSettings::direction),
    // world space, any length > 0; used only when hasLight. It picks the pixels facing the light
    // for the shadow metrics; without it they use every pixel covered in both.
    glm::dvec3 lightDirection{0.0, 0.0, -1.0};
    bool hasLight = false;
    // Radius of the interior mask's erosion, pixels, >= 0 (masks.h).
    int interiorRadius = 2;
};

// The masks the metrics are taken over (masks.h), for these settings.
MaskSettings maskSettings(const MetricSettings& settings);

struct MetricResult {
    // By metric key (metric_table.h): the table's AnyPair metrics (beauty.psnr, beauty.ssim,
    // beauty.flip and its pooled statistics) for every pair, its AovPair ones too for AOV images. A
    // metric whose mask is empty is NaN (and silhouette.mean_px is +inf when only one image has an
    // outline): a JSON writer must map both.
    std::map<std::string, double> values;
    // One-channel float images of the pair's size: "beauty.flip" always; for AOV images also
    // "beauty.hdrflip" (HDR-ꟻLIP's largest error over the exposures), "normal" (angle, degrees),
    // "depth" (relative error), "uv" (seam-aware uv distance), "id" (1 where the visible body
    // differs), "shadow" (1 false, 2 missed shadow) and "emission" (per-pixel RMS over R, G, B),
    // each 0 where its mask does not reach.
    std::map<std::string, core::Image> errorMaps;
    // AOV images: the exposures beauty.hdrflip was taken over (hdr_flip.h), to report beside it.
    std::optional<ExposureRange> hdrExposures;
    // AOV images: the metrics of the metric table that the images' channels cannot give (a
    // channel missing from either), in the table's order of computation; and the AOV channels
    // either image lacks.
    std::vector<std::string> notProvided;
    std::vector<std::string> missingChannels;
    // Metrics computed but meaningless for this pair, with why: their buffer holds nothing in
    // either image (the ao.* metrics where neither render has any occlusion, emission.rmse
    // where neither has any emission). Their values stay (0); the reports show "n/a" and the
    // thresholds leave them unchecked.
    std::map<std::string, std::string> notApplicable;
};

// True when the image carries an AOV channel other than R, G, B, A (its R, G, B then linear);
// false for a display image.
bool isAovImage(const core::Image& image);
// The AOV channels (core::aov::channelNames()) the image lacks, in that order.
std::vector<std::string> missingAovChannels(const core::Image& image);

// Throws core::NotComparableError when the sizes differ (the message names both), when either
// image lacks R, G or B, or when one is an AOV image and the other is not (the message names
// the channels it has); std::invalid_argument for settings out of range.
MetricResult computeMetrics(const core::Image& reference, const core::Image& test,
                            const MetricSettings& settings = {});

}  // namespace twinrender::compare
