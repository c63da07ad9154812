// The JSON files of a run (docs/design.md, "Thresholds and baselines"): per-scene metrics.json and
// summary.json, and the whole scene report that `merge` reads back from the shards of a run.
// Non-finite metric values as json_number.h writes them.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "report/report.h"

namespace twinrender::report {

// {"scene", "description", "status", "metrics": {key: value}, "checks": [{"metric", "value",
//  "bound", "limit", "status", "message", ["baseline", "delta"]}], "timings_ms",
//  "error_maps": {buffer: {"path", "label", "lo", "hi", "unit"}}, ["error"], ["sequence":
//  {"fps", "frames": [{"frame", "metrics"}], "shown_frame", "videos", "charts"}]}
nlohmann::json metricsJson(const SceneReport& scene);
// {"status", "scenes": [{"name", "status", "metrics", "timings_ms": {renderer: {stage: ms}},
//  "checks", "settings", ["error"]}], "thresholds", "baseline", "created"}
nlohmann::json summaryJson(const RunReport& run);

// Atomic writes (temporary name, then rename).
void writeMetricsJson(const SceneReport& scene, const std::filesystem::path& file);
void writeSummaryJson(const RunReport& run, const std::filesystem::path& file);

// Every field of a scene's report as JSON (metricsJson's keys plus "baseline", "renderers"
// with timings, device, counters and images, and "settings"), and back:
// sceneReportFromJson(sceneReportJson(s)) reproduces s, so shards of a run can be merged into
// the report one run writes. Throws core::InputError naming `source` for malformed JSON.
nlohmann::json sceneReportJson(const SceneReport& scene);
SceneReport sceneReportFromJson(const nlohmann::json& json, const std::string& source);

}  // namespace twinrender::report
