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
    static const std::vector<MetricInfo> table = {
        // key, unit, better, origin, noise, buffer, source, overview, machine-dependent,
        // meaning
        {"beauty.psnr", "dB", B::Higher, 0.0, 0.1, "beauty", S::AnyPair, true, false,
         "peak signal-to-noise ratio of the tonemapped beauty over R, G, B, peak 1; +inf for "
         "identical images"},
        {"beauty.ssim", "", B::Higher, 1.0, 1e-3, "beauty", S::AnyPair, true, false,
         "structural similarity of the tonemapped beauty, mean over R, G, B (Wang et al. 2004, "
         "Gaussian σ 1.5)"},
        {"beauty.flip", "", B::Lower, 0.0, 1e-3, "beauty", S::AnyPair, true, false,
         "mean LDR-ꟻLIP error of the tonemapped beauty (Andersson et al. 2020), 0 to 1"},
        {"beauty.flip_p95", "", B::Lower, 0.0, 1e-3, "beauty", S::AnyPair, false, false,
         "95th percentile of the per-pixel ꟻLIP error of the tonemapped beauty over every pixel "
         "(numpy's linear method): the error of the worst 5 % of the pixels"},
        {"beauty.flip_p99", "", B::Lower, 0.0, 1e-3, "beauty", S::AnyPair, false, false,
         "99th percentile of that error: the worst 1 %"},
        {"beauty.flip_over", "", B::Lower, 0.0, 1e-3, "beauty", S::AnyPair, false, false,
         "fraction of the pixels whose ꟻLIP error is above the level --flip-over (default 0.5): "
         "rare large errors the mean hides"},
        {"beauty.hdrflip", "", B::Lower, 0.0, 1e-3, "beauty", S::AovPair, false, false,
         "mean HDR-ꟻLIP of the linear beauty (Andersson et al. 2021): per pixel the largest "
         "LDR-ꟻLIP over ACES-tonemapped exposures from the reference's brightest pixel to its "
         "median lit one, 0 to 1"},
        {"coverage.iou", "", B::Higher, 1.0, 1e-3, "A", S::AovPair, true, false,
         "intersection over union of the pixels each render covers"},
        {"silhouette.mean_px", "px", B::Lower, 0.0, 0.05, "A", S::AovPair, true, false,
         "mean distance between the two outlines; inf when only one render has one"},
        {"depth.rel_mean", "", B::Lower, 0.0, 1e-4, "Z", S::AovPair, true, false,
         "mean relative depth error on the pixels both renders cover with the same body"},
        {"id.mismatch", "", B::Lower, 0.0, 1e-3, "id", S::AovPair, true, false,
         "fraction of the pixels covered in both where another body is visible: occlusion order "
         "errors"},
        {"normal.mean_deg", "°", B::Lower, 0.0, 0.1, "N", S::AovPair, true, false,
         "mean angle between the two normals on interior pixels of the same body"},
        {"normal.p95_deg", "°", B::Lower, 0.0, 0.1, "N", S::AovPair, false, false,
         "95th percentile of that angle"},
        {"uv.mean", "", B::Lower, 0.0, 1e-4, "uv", S::AovPair, false, false,
         "mean seam-aware distance between the texture coordinates on interior pixels of the "
         "same body"},
        {"emission.rmse", "", B::Lower, 0.0, 1e-4, "emission", S::AovPair, false, false,
         "root mean square error of the emitted radiance on the pixels covered in both"},
        {"smoothness.ratio", "", B::Closer, 1.0, 0.01, "N", S::AovPair, false, false,
         "roughness of the test's normal field over the reference's: 1 as smooth, above 1 "
         "rougher"},
        {"shadow.iou", "", B::Higher, 1.0, 1e-3, "shadow", S::AovPair, true, false,
         "intersection over union of the shadowed pixels that face the light"},
        {"shadow.false_shadow", "", B::Lower, 0.0, 1e-3, "shadow", S::AovPair, false, false,
         "fraction of the pixels facing the light lit in the reference but shadowed in the "
         "test: acne"},
        {"shadow.missed_shadow", "", B::Lower, 0.0, 1e-3, "shadow", S::AovPair, false, false,
         "fraction shadowed in the reference but lit in the test: leaks, peter-panning"},
        {"occlusion.error", "", B::Lower, 0.0, 1e-3, "id", S::Study, false, false,
         "fraction of the reference's covered pixels where the test shows another body or none"},
        {"contact.uv_mean", "", B::Lower, 0.0, 1e-4, "uv", S::Study, false, false,
         "mean uv distance in the band along the boundary between two bodies: bleeding"},
        {"contact.emission_rmse", "", B::Lower, 0.0, 1e-4, "emission", S::Study, false, false,
         "root mean square emission error in that band"},
        {"contact.pixels", "", B::Higher, 0.0, 0.5, "id", S::Study, false, false,
         "pixels in that band: the sample the contact metrics are taken over"},
        {"temporal.frame_flip", "", B::Lower, 0.0, 1e-3, "beauty", S::Study, false, false,
         "mean ꟻLIP between a real-time frame and the previous one of its series or sequence"},
        {"temporal.reference_frame_flip", "", B::Lower, 0.0, 1e-3, "beauty", S::Study, false, false,
         "the same between consecutive reference frames: what the motion itself changes"},
        {"temporal.flicker", "", B::Lower, 0.0, 1e-3, "beauty", S::Sequence, false, false,
         "per frame of a sequence: the real-time renders' frame-to-frame ꟻLIP minus the "
         "reference's, the change the truth does not have (motion is not counted)"},
        {"temporal.flicker_mean", "", B::Lower, 0.0, 1e-3, "beauty", S::Sequence, true, false,
         "temporal.flicker, mean over the frames of a sequence"},
        {"temporal.flicker_max", "", B::Lower, 0.0, 1e-3, "beauty", S::Sequence, false, false,
         "temporal.flicker, largest over the frames of a sequence"},
        {"temporal.normal_change_deg", "°", B::Lower, 0.0, 0.1, "N", S::Sequence, false, false,
         "mean angle between a real-time frame's normals and the previous frame's, over the "
         "pixels covered in both frames of both renders"},
        {"temporal.reference_normal_change_deg", "°", B::Lower, 0.0, 0.1, "N", S::Sequence, false,
         false, "the same between consecutive reference frames"},
        {"temporal.normal_flicker_deg", "°", B::Lower, 0.0, 0.1, "N", S::Sequence, false, false,
         "per frame: the real-time normal change minus the reference's"},
        {"temporal.normal_flicker_mean_deg", "°", B::Lower, 0.0, 0.1, "N", S::Sequence, false,
         false, "temporal.normal_flicker_deg, mean over the frames of a sequence"},
        {"temporal.normal_flicker_max_deg", "°", B::Lower, 0.0, 0.1, "N", S::Sequence, false, false,
         "temporal.normal_flicker_deg, largest over the frames of a sequence"},
        {"time.<renderer>_ms", "ms", B::Lower, 0.0, 1.0, "", S::Render, false, true,
         "the renderer's time for the frame, without start-up and file I/O"},
        {"count.<counter>", "", B::Lower, 0.0, 0.5, "", S::Render, false, false,
         "a counter of the test render: work done (particles_drawn, field_evaluations) or rays "
         "given up (unbracketed_rays)"},
    };
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
