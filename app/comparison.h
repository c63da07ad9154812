// One scene's two renders compared: the metrics, the checks against thresholds and baseline,
// and the images and JSON of the scene's folder in a run. Shared by `run` (and `sweep`).
#pragma once

#include <filesystem>
#include <optional>

#include "app/render_job.h"
#include "compare/baseline.h"
#include "compare/metrics.h"
#include "compare/thresholds.h"
#include "report/report.h"

namespace twinrender::app {

// Metric settings for a scene: its light and exposure, FLIP's pixels per degree and the error
// level of beauty.flip_over.
compare::MetricSettings metricSettings(const LoadedScene& scene, double ppd,
                                       double flipOver = compare::MetricSettings{}.flipOver);

// Compares the real-time render (test) with the reference (ref), writes the scene folder's
// images (per-buffer PNGs of both renders, colour-mapped error maps) and returns the scene's
// report with its checks. `bounds` from the thresholds; `baseline` may be null.
report::SceneReport compareScene(const LoadedScene& scene, const core::Frame& ref,
                                 const core::Frame& test, const compare::Bounds& bounds,
                                 const compare::Baseline* baseline, double ppd, double flipOver,
                                 const std::filesystem::path& sceneDir);

// The same for metrics already computed (compare::computeMetrics of the pair): the report,
// its checks, and the scene folder's images.
report::SceneReport sceneReport(const LoadedScene& scene, const core::Frame& ref,
                                const core::Frame& test, const compare::MetricResult& result,
                                const compare::Bounds& bounds, const compare::Baseline* baseline,
                                const std::filesystem::path& sceneDir);

// Sets the report's checks: its metrics against `bounds`, and against the baseline's metrics
// of the scene when `baseline` is not null (also setting report.baseline). The report's name
// and settings must be set.
void checkReport(report::SceneReport& report, const compare::Bounds& bounds,
                 const compare::Baseline* baseline);

// The exposures beauty.hdrflip was taken over, as a report's settings show them:
// {"hdrflip": {"start_exposure", "stop_exposure", "exposures"}} (stops, and their count).
nlohmann::json hdrExposuresJson(const compare::ExposureRange& range);

// The time a report is written, "2026-11-21 16:40 UTC".
std::string nowUtc();

// The image metrics each part of the error split is measured by (core::Frame::split), as
// PART.METRIC: surface.beauty.flip, lighting.beauty.flip, shading.beauty.flip, ...
inline constexpr const char* SPLIT_METRICS[] = {"beauty.flip", "beauty.psnr", "beauty.ssim"};
// Adds the error split's metrics when the test frame has its images: each part's image
// tonemapped and compared with the reference's tonemapped beauty.
void addSplitMetrics(const core::Frame& ref, const core::Frame& test,
                     const compare::MetricSettings& settings, compare::MetricValues& metrics);

// The time metrics of a pair of renders: time.<renderer>_ms (total) of each that has one.
void addTimeMetrics(const core::Frame& ref, const core::Frame& test,
                    compare::MetricValues& metrics);

}  // namespace twinrender::app
