#include "app/comparison.h"

#include <algorithm>
#include <ctime>

#include "compare/error_maps.h"
#include "report/buffer_display.h"

namespace twinrender::app {

compare::MetricSettings metricSettings(const LoadedScene& s, double ppd, double flipOver) {
    compare::MetricSettings m;
    m.ppd = ppd;
    m.flipOver = flipOver;
    m.exposure = s.scene.camera.exposure;
    m.lightDirection = s.scene.light.direction;
    m.hasLight = true;
    return m;
}

void addTimeMetrics(const core::Frame& ref, const core::Frame& test,
                    compare::MetricValues& metrics) {
    // Images rendered earlier may come without their times (app/test_images.h).
    for (const core::Frame* f : {&test, &ref})
        if (const auto total = f->timingsMs.find("total"); total != f->timingsMs.end())
            metrics["time." + f->renderer + "_ms"] = total->second;
}

void addSplitMetrics(const core::Frame& ref, const core::Frame& test,
                     const compare::MetricSettings& settings, compare::MetricValues& metrics) {
    if (test.split.empty()) return;
    const float exposure = static_cast<float>(settings.exposure);
    const core::Image reference = core::tonemappedBeauty(ref.image, exposure);
    for (const auto& [part, image] : test.split) {
        const compare::MetricResult r =
            compare::computeMetrics(reference, core::tonemappedBeauty(image, exposure), settings);
        for (const char* metric : SPLIT_METRICS) metrics[part + "." + metric] = r.values.at(metric);
    }
}

report::SceneReport compareScene(const LoadedScene& s, const core::Frame& ref,
                                 const core::Frame& test, const compare::Bounds& bounds,
                                 const compare::Baseline* baseline, double ppd, double flipOver,
                                 const std::filesystem::path& dir) {
    const compare::MetricSettings settings = metricSettings(s, ppd, flipOver);
    compare::MetricResult result = compare::computeMetrics(ref.image, test.image, settings);
    addSplitMetrics(ref, test, settings, result.values);
    return sceneReport(s, ref, test, result, bounds, baseline, dir);
}

report::SceneReport sceneReport(const LoadedScene& s, const core::Frame& ref,
                                const core::Frame& test, const compare::MetricResult& result,
                                const compare::Bounds& bounds, const compare::Baseline* baseline,
                                const std::filesystem::path& dir) {
    report::SceneReport report;
    report.name = s.scene.name;
    report.description = s.scene.description;
    report.metrics = result.values;
    report.notProvided = result.notProvided;
    report.notApplicable = result.notApplicable;
    addTimeMetrics(ref, test, report.metrics);

    report.settings = {{"scene_file", s.scene.file.string()},
                       {ref.renderer, ref.settings},
                       {test.renderer, test.settings}};
    if (result.hdrExposures) report.settings["compare"] = hdrExposuresJson(*result.hdrExposures);
    checkReport(report, bounds, baseline);

    report::BufferVisualSettings visual;
    visual.exposure = static_cast<float>(s.scene.camera.exposure);
    visual.depthRange = report::depthRange(ref.image, test.image);
    for (const core::Frame* r : {&ref, &test}) {
        report::RendererReport rr;
        rr.timingsMs = r->timingsMs;
        rr.device = r->device;
        rr.counters = r->counters;
        rr.images = report::writeBufferImages(r->image, &r->display, dir, r->renderer, visual);
        report.renderers[r->renderer] = std::move(rr);
    }
    report.errorMaps = compare::writeErrorMapImages(result.errorMaps, dir);
    return report;
}

void checkReport(report::SceneReport& report, const compare::Bounds& bounds,
                 const compare::Baseline* baseline) {
    // A metric the test image does not provide, or that does not apply to the scene, is never
    // checked (never a pass, never a fail).
    const compare::Bounds provided = compare::filterBounds(bounds, [&](const std::string& m) {
        return std::find(report.notProvided.begin(), report.notProvided.end(), m) ==
                   report.notProvided.end() &&
               !report.notApplicable.count(m);
    });
    report.checks = compare::evaluate(report.metrics, provided);
    if (baseline) {
        if (const auto* blessed = baseline->metrics(report.name)) report.baseline = *blessed;
        auto more =
            compare::compareToBaseline(report.name, report.metrics, *baseline, &report.settings);
        report.checks.insert(report.checks.end(), more.begin(), more.end());
    }
}

nlohmann::json hdrExposuresJson(const compare::ExposureRange& range) {
    return {{"hdrflip",
             {{"start_exposure", range.start},
              {"stop_exposure", range.stop},
              {"exposures", range.count}}}};
}

std::string nowUtc() {
    const std::time_t t = std::time(nullptr);
    char buf[64];
    std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
    return buf;
}

}  // namespace twinrender::app
