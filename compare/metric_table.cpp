#include "compare/metric_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <tuple>

namespace twinrender::compare {

std::string_view toString(Better better) {
    switch (better) {
        case Better::Higher:
            return "higher";
        case Better::Lower:
            return "lower";
        case Better::Closer:
            return "closer";
    }
    return "lower";
}

const std::vector<MetricInfo>& metricTable() {
    using B = Better;
    using S = MetricSource;
    // Noise: 0.1 dB and 0.1 degree, 0.05 px, 1e-3 of a fraction of pixels or of SSIM and IoU,
    // 1e-4 of relative depth, uv and emission; 1 ms; half a count.
    // A row in a few lines (clang-format would give every field a line of its own).
    // clang-format off
    static const std::vector<MetricInfo> table = {
        {.key = "beauty.psnr", .unit = "dB", .better = B::Higher, .origin = 0.0, .noise = 0.1,
         .buffer = "beauty", .source = S::AnyPair, .overview = true, .machineDependent = false,
         .meaning = "peak signal-to-noise ratio of the tonemapped beauty over R, G, B, peak 1; "
                    "+inf for identical images"},
        {.key = "beauty.ssim", .unit = "", .better = B::Higher, .origin = 1.0, .noise = 1e-3,
         .buffer = "beauty", .source = S::AnyPair, .overview = true, .machineDependent = false,
         .meaning = "structural similarity of the tonemapped beauty, mean over R, G, B (Wang et"
                    " al. 2004, Gaussian σ 1.5)"},
        {.key = "beauty.flip", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "beauty", .source = S::AnyPair, .overview = true, .machineDependent = false,
         .meaning = "mean LDR-ꟻLIP error of the tonemapped beauty (Andersson et al. 2020), 0 to"
                    " 1"},
        {.key = "beauty.flip_p95", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "beauty", .source = S::AnyPair, .overview = false, .machineDependent = false,
         .meaning = "95th percentile of the per-pixel ꟻLIP error of the tonemapped beauty over "
                    "every pixel (numpy's linear method): the error of the worst 5 % of the "
                    "pixels"},
        {.key = "beauty.flip_p99", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "beauty", .source = S::AnyPair, .overview = false, .machineDependent = false,
         .meaning = "99th percentile of that error: the worst 1 %"},
        {.key = "beauty.flip_over", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "beauty", .source = S::AnyPair, .overview = false, .machineDependent = false,
         .meaning = "fraction of the pixels whose ꟻLIP error is above the level --flip-over "
                    "(default 0.5): rare large errors the mean hides"},
        {.key = "beauty.hdrflip", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "beauty", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "mean HDR-ꟻLIP of the linear beauty (Andersson et al. 2021): per pixel the "
                    "largest LDR-ꟻLIP over ACES-tonemapped exposures from the reference's "
                    "brightest pixel to its median lit one, 0 to 1"},
        {.key = "coverage.iou", .unit = "", .better = B::Higher, .origin = 1.0, .noise = 1e-3,
         .buffer = "A", .source = S::AovPair, .overview = true, .machineDependent = false,
         .meaning = "intersection over union of the pixels each render covers"},
        {.key = "silhouette.mean_px", .unit = "px", .better = B::Lower, .origin = 0.0,
         .noise = 0.05, .buffer = "A", .source = S::AovPair, .overview = true,
         .machineDependent = false,
         .meaning = "mean distance between the two outlines; inf when only one render has one"},
        {.key = "depth.rel_mean", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-4,
         .buffer = "Z", .source = S::AovPair, .overview = true, .machineDependent = false,
         .meaning = "mean relative depth error on the pixels both renders cover with the same "
                    "body"},
        {.key = "id.mismatch", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "id", .source = S::AovPair, .overview = true, .machineDependent = false,
         .meaning = "fraction of the pixels covered in both where another body is visible: "
                    "occlusion order errors"},
        {.key = "normal.mean_deg", .unit = "°", .better = B::Lower, .origin = 0.0, .noise = 0.1,
         .buffer = "N", .source = S::AovPair, .overview = true, .machineDependent = false,
         .meaning = "mean angle between the two normals on interior pixels of the same body"},
        {.key = "normal.p95_deg", .unit = "°", .better = B::Lower, .origin = 0.0, .noise = 0.1,
         .buffer = "N", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "95th percentile of that angle"},
        {.key = "uv.mean", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-4,
         .buffer = "uv", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "mean seam-aware distance between the texture coordinates on interior "
                    "pixels of the same body"},
        {.key = "emission.rmse", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-4,
         .buffer = "emission", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "root mean square error of the emitted radiance on the pixels covered in "
                    "both"},
        {.key = "flux.ratio", .unit = "", .better = B::Closer, .origin = 1.0, .noise = 1e-3,
         .buffer = "beauty", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "sum of the test's linear beauty (R + G + B, every pixel) over the "
                    "reference's: 1 the same light, below 1 light lost (a sub-pixel emitter)"},
        {.key = "smoothness.ratio", .unit = "", .better = B::Closer, .origin = 1.0, .noise = 0.01,
         .buffer = "N", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "roughness of the test's normal field over the reference's: 1 as smooth, "
                    "above 1 rougher"},
        {.key = "shadow.iou", .unit = "", .better = B::Higher, .origin = 1.0, .noise = 1e-3,
         .buffer = "shadow", .source = S::AovPair, .overview = true, .machineDependent = false,
         .meaning = "intersection over union of the shadowed pixels that face the light"},
        {.key = "shadow.false_shadow", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "shadow", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "fraction of the pixels facing the light lit in the reference but shadowed "
                    "in the test: acne"},
        {.key = "shadow.missed_shadow", .unit = "", .better = B::Lower, .origin = 0.0,
         .noise = 1e-3, .buffer = "shadow", .source = S::AovPair, .overview = false,
         .machineDependent = false,
         .meaning = "fraction shadowed in the reference but lit in the test: leaks, peter-"
                    "panning"},
        {.key = "shadow.mae", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "shadow", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "mean absolute error of the sun's visibility (0 to 1, fractional in "
                    "penumbrae) over the pixels facing the light"},
        {.key = "shadow.leak", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "shadow", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "fraction of the pixels facing the light that the test lights (visibility "
                    "above 0.5) where the reference is in full shadow (visibility 0): light "
                    "bleeding into the umbra"},
        {.key = "ao.mean_abs", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "ao", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "mean absolute error of the ambient occlusion (the open fraction of the "
                    "hemisphere within light.ao_radius) on the pixels covered in both"},
        {.key = "ao.bias", .unit = "", .better = B::Closer, .origin = 0.0, .noise = 1e-3,
         .buffer = "ao", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "mean signed error of that occlusion: positive too light (occlusion "
                    "missed), negative too dark (occlusion invented)"},
        {.key = "ao.halo", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "ao", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "mean absolute occlusion error within 4 pixels of the reference's depth "
                    "edges, where screen-space occlusion cannot see behind the surface"},
        {.key = "ao.grain", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "ao", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "RMS of the occlusion error finer than 9 px on interior pixels: the noise a "
                    "blur leaves"},
        {.key = "ao.banding", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "ao", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "RMS of the occlusion error's 9 px local mean about its mean: blotches and "
                    "bands coarser than the blur"},
        {.key = "ao.false", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "ao", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "mean occlusion the test adds where the reference is open (open fraction at "
                    "least 0.99): occlusion invented across a gap or by the impostors' bumps"},
        {.key = "ao.missed", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "ao", .source = S::AovPair, .overview = false, .machineDependent = false,
         .meaning = "share of the reference's occlusion the test leaves out where the reference "
                    "is occluded (open fraction below 0.9): 0 all found, 1 none"},
        {.key = "indirect.rmse", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "irradiance", .source = S::AovPair, .overview = false,
         .machineDependent = false,
         .meaning = "RMS error of the irradiance from emitting surfaces (its luminance, "
                    "light.emissive_light) on the pixels covered in both"},
        {.key = "indirect.missed", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "irradiance", .source = S::AovPair, .overview = false,
         .machineDependent = false,
         .meaning = "fraction of the pixels the emitters light in the reference (above 5 % of "
                    "its 99th percentile) that the test leaves dark: hidden or off-screen "
                    "emitters"},
        {.key = "indirect.false", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "irradiance", .source = S::AovPair, .overview = false,
         .machineDependent = false,
         .meaning = "fraction of the pixels dark in the reference that the test lights: light "
                    "through occluders"},
        {.key = "inscatter.rmse", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-4,
         .buffer = "inscatter", .source = S::AovPair, .overview = false,
         .machineDependent = false,
         .meaning = "RMS error of a body's atmosphere's in-scatter (its luminance) on the pixels "
                    "where either frame has any: the real-time end point against the exact hit"},
        {.key = "inscatter.rel", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "inscatter", .source = S::AovPair, .overview = false,
         .machineDependent = false,
         .meaning = "inscatter.rmse over the RMS of the reference's in-scatter on the same "
                    "pixels"},
        {.key = "surface.beauty.flip", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "beauty", .source = S::Render, .overview = false, .machineDependent = false,
         .meaning = "the error split's surface part: ꟻLIP of the real-time surface shaded with "
                    "the reference's shadow and occlusion, against the reference"},
        {.key = "lighting.beauty.flip", .unit = "", .better = B::Lower, .origin = 0.0,
         .noise = 1e-3, .buffer = "beauty", .source = S::Render, .overview = false,
         .machineDependent = false,
         .meaning = "the error split's lighting part: ꟻLIP of the reference's surface shaded "
                    "with the real-time shadow and occlusion, against the reference"},
        {.key = "shading.beauty.flip", .unit = "", .better = B::Lower, .origin = 0.0,
         .noise = 1e-3, .buffer = "beauty", .source = S::Render, .overview = false,
         .machineDependent = false,
         .meaning = "the error split's floor: ꟻLIP of the reference's surface and light shaded "
                    "by the real-time shader, against the reference (rounding)"},
        {.key = "surface.beauty.psnr", .unit = "dB", .better = B::Higher, .origin = 0.0,
         .noise = 0.05, .buffer = "beauty", .source = S::Render, .overview = false,
         .machineDependent = false, .meaning = "PSNR of the error split's surface part"},
        {.key = "lighting.beauty.psnr", .unit = "dB", .better = B::Higher, .origin = 0.0,
         .noise = 0.05, .buffer = "beauty", .source = S::Render, .overview = false,
         .machineDependent = false, .meaning = "PSNR of the error split's lighting part"},
        {.key = "shading.beauty.psnr", .unit = "dB", .better = B::Higher, .origin = 0.0,
         .noise = 0.05, .buffer = "beauty", .source = S::Render, .overview = false,
         .machineDependent = false, .meaning = "PSNR of the error split's floor"},
        {.key = "surface.beauty.ssim", .unit = "", .better = B::Higher, .origin = 1.0, .noise = 1e-4,
         .buffer = "beauty", .source = S::Render, .overview = false, .machineDependent = false,
         .meaning = "SSIM of the error split's surface part"},
        {.key = "lighting.beauty.ssim", .unit = "", .better = B::Higher, .origin = 1.0,
         .noise = 1e-4, .buffer = "beauty", .source = S::Render, .overview = false,
         .machineDependent = false, .meaning = "SSIM of the error split's lighting part"},
        {.key = "shading.beauty.ssim", .unit = "", .better = B::Higher, .origin = 1.0,
         .noise = 1e-4, .buffer = "beauty", .source = S::Render, .overview = false,
         .machineDependent = false, .meaning = "SSIM of the error split's floor"},
        {.key = "occlusion.error", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "id", .source = S::Study, .overview = false, .machineDependent = false,
         .meaning = "fraction of the reference's covered pixels where the test shows another "
                    "body or none"},
        {.key = "contact.uv_mean", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-4,
         .buffer = "uv", .source = S::Study, .overview = false, .machineDependent = false,
         .meaning = "mean uv distance in the band along the boundary between two bodies: "
                    "bleeding"},
        {.key = "contact.emission_rmse", .unit = "", .better = B::Lower, .origin = 0.0,
         .noise = 1e-4, .buffer = "emission", .source = S::Study, .overview = false,
         .machineDependent = false,
         .meaning = "root mean square emission error in that band"},
        {.key = "contact.pixels", .unit = "", .better = B::Higher, .origin = 0.0, .noise = 0.5,
         .buffer = "id", .source = S::Study, .overview = false, .machineDependent = false,
         .meaning = "pixels in that band: the sample the contact metrics are taken over"},
        {.key = "temporal.frame_flip", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "beauty", .source = S::Study, .overview = false, .machineDependent = false,
         .meaning = "mean ꟻLIP between a real-time frame and the previous one of its series or "
                    "sequence"},
        {.key = "temporal.reference_frame_flip", .unit = "", .better = B::Lower, .origin = 0.0,
         .noise = 1e-3, .buffer = "beauty", .source = S::Study, .overview = false,
         .machineDependent = false,
         .meaning = "the same between consecutive reference frames: what the motion itself "
                    "changes"},
        {.key = "temporal.flicker", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 1e-3,
         .buffer = "beauty", .source = S::Sequence, .overview = false, .machineDependent = false,
         .meaning = "per frame of a sequence: the real-time renders' frame-to-frame ꟻLIP minus "
                    "the reference's, the change the truth does not have (motion is not "
                    "counted)"},
        {.key = "temporal.flicker_mean", .unit = "", .better = B::Lower, .origin = 0.0,
         .noise = 1e-3, .buffer = "beauty", .source = S::Sequence, .overview = true,
         .machineDependent = false,
         .meaning = "temporal.flicker, mean over the frames of a sequence"},
        {.key = "temporal.flicker_max", .unit = "", .better = B::Lower, .origin = 0.0,
         .noise = 1e-3, .buffer = "beauty", .source = S::Sequence, .overview = false,
         .machineDependent = false,
         .meaning = "temporal.flicker, largest over the frames of a sequence"},
        {.key = "temporal.normal_change_deg", .unit = "°", .better = B::Lower, .origin = 0.0,
         .noise = 0.1, .buffer = "N", .source = S::Sequence, .overview = false,
         .machineDependent = false,
         .meaning = "mean angle between a real-time frame's normals and the previous frame's, "
                    "over the pixels covered in both frames of both renders"},
        {.key = "temporal.reference_normal_change_deg", .unit = "°", .better = B::Lower,
         .origin = 0.0, .noise = 0.1, .buffer = "N", .source = S::Sequence, .overview = false,
         .machineDependent = false,
         .meaning = "the same between consecutive reference frames"},
        {.key = "temporal.normal_flicker_deg", .unit = "°", .better = B::Lower, .origin = 0.0,
         .noise = 0.1, .buffer = "N", .source = S::Sequence, .overview = false,
         .machineDependent = false,
         .meaning = "per frame: the real-time normal change minus the reference's"},
        {.key = "temporal.normal_flicker_mean_deg", .unit = "°", .better = B::Lower, .origin = 0.0,
         .noise = 0.1, .buffer = "N", .source = S::Sequence, .overview = false,
         .machineDependent = false,
         .meaning = "temporal.normal_flicker_deg, mean over the frames of a sequence"},
        {.key = "temporal.normal_flicker_max_deg", .unit = "°", .better = B::Lower, .origin = 0.0,
         .noise = 0.1, .buffer = "N", .source = S::Sequence, .overview = false,
         .machineDependent = false,
         .meaning = "temporal.normal_flicker_deg, largest over the frames of a sequence"},
        {.key = "time.<renderer>_ms", .unit = "ms", .better = B::Lower, .origin = 0.0, .noise = 1.0,
         .buffer = "", .source = S::Render, .overview = false, .machineDependent = true,
         .meaning = "the renderer's time for the frame, without start-up and file I/O"},
        {.key = "count.<counter>", .unit = "", .better = B::Lower, .origin = 0.0, .noise = 0.5,
         .buffer = "", .source = S::Render, .overview = false, .machineDependent = false,
         .meaning = "a counter of the test render: work done (particles_drawn, "
                    "field_evaluations) or rays given up (unbracketed_rays)"},
    };
    // clang-format on
    return table;
}

namespace {

// Whether `key` is a member of `family` ("time.<renderer>_ms"): the text around the angle
// brackets matches and the variable part is not empty.
bool inFamily(std::string_view family, std::string_view key) {
    const auto open = family.find('<'), close = family.find('>');
    if (open == std::string_view::npos || close == std::string_view::npos) return false;
    const std::string_view head = family.substr(0, open), tail = family.substr(close + 1);
    return key.size() > head.size() + tail.size() && key.substr(0, head.size()) == head &&
           key.substr(key.size() - tail.size()) == tail;
}

// The entry's index in the table; the table's size for an unknown key.
std::size_t rank(std::string_view key) {
    const auto& t = metricTable();
    if (const MetricInfo* m = findMetric(key)) return static_cast<std::size_t>(m - t.data());
    return t.size();
}

}  // namespace

const MetricInfo* findMetric(std::string_view key) {
    const auto& t = metricTable();
    for (const MetricInfo& m : t)
        if (m.key == key) return &m;
    for (const MetricInfo& m : t)
        if (inFamily(m.key, key)) return &m;
    return nullptr;
}

std::string metricNames(bool comparisonOnly) {
    std::string names;
    for (const MetricInfo& m : metricTable())
        if (!comparisonOnly || computedByComparison(m.key))
            names += (names.empty() ? "" : ", ") + std::string(m.key);
    return names;
}

std::string metricDescription(std::string_view key) {
    const MetricInfo* m = findMetric(key);
    if (!m) return "";
    const std::string direction = m->better == Better::Closer
                                      ? fmt::format("closest to {:g} is best", m->origin)
                                      : fmt::format("{} is better", toString(m->better));
    return fmt::format("{} ({})", m->meaning, direction);
}

std::string metricUnit(std::string_view key) {
    const MetricInfo* m = findMetric(key);
    return m ? std::string(m->unit) : "";
}

bool metricLess(std::string_view a, std::string_view b) {
    return std::forward_as_tuple(rank(a), a) < std::forward_as_tuple(rank(b), b);
}

std::vector<std::string> inMetricOrder(std::vector<std::string> keys) {
    std::sort(keys.begin(), keys.end(),
              [](const std::string& a, const std::string& b) { return metricLess(a, b); });
    return keys;
}

bool computedByComparison(std::string_view key) {
    const MetricInfo* m = findMetric(key);
    return m && (m->source == MetricSource::AnyPair || m->source == MetricSource::AovPair);
}

bool computedOnPlainImages(std::string_view key) {
    const MetricInfo* m = findMetric(key);
    return m && m->source == MetricSource::AnyPair;
}

}  // namespace twinrender::compare
