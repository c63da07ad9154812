#include "app/comparison.h"

#include <ctime>

#include "compare/buffer_display.h"
#include "compare/error_maps.h"

namespace twinrender::app {

compare::MetricSettings metricSettings(const LoadedScene& s, double ppd) {
    compare::MetricSettings m;
    m.ppd = ppd;
    m.exposure = s.scene.camera.exposure;
    m.lightDirection = s.scene.light.direction;
    m.hasLight = true;
    return m;
}

void addTimeMetrics(const Render& ref, const Render& test, compare::MetricValues& metrics) {
    metrics["time." + test.frame.renderer + "_ms"] = test.frame.timingsMs.at("total");
    metrics["time." + ref.frame.renderer + "_ms"] = ref.frame.timingsMs.at("total");
}

compare::SceneReport compareScene(const LoadedScene& s, const Render& ref, const Render& test,
                                  const compare::Bounds& bounds, const compare::Baseline* baseline,
                                  double ppd, const std::filesystem::path& dir) {
    compare::SceneReport report;
    report.name = s.scene.name;
    report.description = s.scene.description;
    const compare::MetricResult result =
        compare::computeMetrics(ref.frame.image, test.frame.image, metricSettings(s, ppd));
    report.metrics = result.values;
    addTimeMetrics(ref, test, report.metrics);

    report.settings = {{"scene_file", s.scene.file.string()},
                       {ref.frame.renderer, ref.frame.settings},
                       {test.frame.renderer, test.frame.settings}};
    report.checks = compare::evaluate(report.metrics, bounds);
    if (baseline) {
        if (const auto* blessed = baseline->metrics(s.scene.name)) report.baseline = *blessed;
        auto more = compare::compareToBaseline(s.scene.name, report.metrics, *baseline, &report.settings);
        report.checks.insert(report.checks.end(), more.begin(), more.end());
    }

    compare::BufferVisualSettings visual;
    visual.exposure = static_cast<float>(s.scene.camera.exposure);
    visual.depthRange = compare::depthRange(ref.frame.image, test.frame.image);
    for (const Render* r : {&ref, &test}) {
        compare::RendererReport rr;
        rr.timingsMs = r->frame.timingsMs;
        rr.device = r->frame.device;
        rr.counters = r->frame.counters;
        rr.images = compare::writeBufferImages(r->frame.image, &r->display, dir, r->frame.renderer, visual);
        report.renderers[r->frame.renderer] = std::move(rr);
    }
    report.errorMaps = compare::writeErrorMapImages(result.errorMaps, dir);
    return report;
}

std::string nowUtc() {
    const std::time_t t = std::time(nullptr);
    char buf[64];
    std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
    return buf;
}

}  // namespace twinrender::app
