#include "app/comparison.h"

#include <ctime>

namespace twinrender::app {

const std::vector<ErrorMapStyle>& errorMapStyles() {
    // Ranges: where the colour map saturates, chosen so that a typical real-time error sits
    // mid-range: ꟻLIP is in [0, 1]; normals beyond 30 degrees are plainly wrong; 5 % depth
    // and 0.05 of uv are far beyond smoothing noise; shadow codes are 1 (false) and 2 (missed).
    static const std::vector<ErrorMapStyle> styles = {
        {"beauty.flip", "beauty", "ꟻLIP error", 0.0, 1.0, ""},
        {"normal", "normal", "normal error", 0.0, 30.0, "°"},
        {"uv", "uv", "uv error", 0.0, 0.05, ""},
        {"depth", "depth", "relative depth error", 0.0, 0.05, ""},
        {"id", "id", "visible body differs", 0.0, 1.0, ""},
        {"shadow", "shadow", "shadow: 1 false, 2 missed", 0.0, 2.0, ""},
        {"emission", "emission", "emission error", 0.0, 1.0, ""},
    };
    return styles;
}

compare::MetricSettings metricSettings(const LoadedScene& s, double ppd) {
    compare::MetricSettings m;
    m.ppd = ppd;
    m.exposure = s.scene.camera.exposure;
    m.lightDirection = s.scene.light.direction;
    m.hasLight = true;
    return m;
}

void addTimeMetrics(const core::Frame& ref, const core::Frame& test,
                    compare::MetricValues& metrics) {
    metrics["time." + test.renderer + "_ms"] = test.timingsMs.at("total");
    metrics["time." + ref.renderer + "_ms"] = ref.timingsMs.at("total");
}

compare::SceneReport compareScene(const LoadedScene& s, const core::Frame& ref,
                                  const core::Frame& test, const compare::Bounds& bounds,
                                  const compare::Baseline* baseline, double ppd,
                                  const std::filesystem::path& dir) {
    compare::SceneReport report;
    report.name = s.scene.name;
    report.description = s.scene.description;
    const compare::MetricResult result =
        compare::computeMetrics(ref.image, test.image, metricSettings(s, ppd));
    report.metrics = result.values;
    addTimeMetrics(ref, test, report.metrics);

    report.settings = {{"scene_file", s.scene.file.string()},
                       {ref.renderer, ref.settings},
                       {test.renderer, test.settings}};
    report.checks = compare::evaluate(report.metrics, bounds);
    if (baseline) {
        if (const auto* blessed = baseline->metrics(s.scene.name)) report.baseline = *blessed;
        auto more = compare::compareToBaseline(s.scene.name, report.metrics, *baseline, &report.settings);
        report.checks.insert(report.checks.end(), more.begin(), more.end());
    }

    compare::BufferVisualSettings visual;
    visual.exposure = static_cast<float>(s.scene.camera.exposure);
    visual.depthRange = compare::depthRange(ref.image, test.image);
    for (const core::Frame* r : {&ref, &test}) {
        compare::RendererReport rr;
        rr.timingsMs = r->timingsMs;
        rr.device = r->device;
        rr.counters = r->counters;
        rr.images = compare::writeBufferImages(r->image, &r->display, dir, r->renderer, visual);
        report.renderers[r->renderer] = std::move(rr);
    }
    for (const ErrorMapStyle& style : errorMapStyles()) {
        const auto it = result.errorMaps.find(style.key);
        if (it == result.errorMaps.end()) continue;
        const std::string file = std::string("error.") + style.buffer + ".png";
        compare::writeErrorMapPng(it->second, 0, style.lo, style.hi, dir / file);
        report.errorMaps[style.buffer] = {file, style.label, style.lo, style.hi, style.unit};
    }
    return report;
}

std::string nowUtc() {
    const std::time_t t = std::time(nullptr);
    char buf[64];
    std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
    return buf;
}

}  // namespace twinrender::app
