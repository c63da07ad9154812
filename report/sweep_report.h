// What `twinrender sweep` leaves (docs/cli.md): one row per combination of the
// varied settings with its cost (median time per stage) and every metric, as
// DIR/sweep.json, DIR/sweep.csv, the chart DIR/sweep.svg (time against one metric, Pareto
// front marked) and DIR/index.html (the chart, the table, the command line). A sweep held to
// thresholds (`--thresholds FILE`) also gives each row its verdict, and names the cheapest
// passing combination: the one a scene needs, and no more.
//
// sweep.json:
//   {"format": "twinrender-sweep", "version": 1, "scene", "scene_file", "mode", "test",
//    "reference", "keys": [...], "metric", "better": "lower|higher", "frames", ["sequence"],
//    "combinations", "created", "command", ["thresholds"], "rows": [{"index", "label", "dir",
//    "settings": {key: value}, "timings_ms": {stage: ms, "total": ms}, "metrics": {...},
//    "reference_key", ["error"], ["status": "pass|warn|fail", "failed": [metric...],
//    "warned": [metric...]]}]}
// "thresholds" and the rows' "status", "failed" and "warned" are there only when the sweep
// was held to thresholds; "sequence": true only for a sequence scene. Non-finite numbers are the
// strings "Infinity", "-Infinity", "NaN" (json_number.h).
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "compare/thresholds.h"

namespace twinrender::report {

using compare::Check;
using compare::MetricValues;
using compare::Status;

struct SweepRow {
    std::size_t index = 0;  // position in the cartesian product of the varied settings
    // Varied key -> value as given on the command line, in the order of SweepReport::keys.
    std::vector<std::pair<std::string, std::string>> settings;
    std::map<std::string, double> timingsMs;  // median over the frames: "total" and per stage
    MetricValues metrics;                     // the test render against its reference
    std::string dir;                          // the combination's folder, relative to the sweep's
    std::string referenceKey;  // the reference's cache key (a sequence's: its shown frame's)
    std::string error;         // set when the combination could not be rendered
    // Against the sweep's thresholds, when it has them: the verdict (Fail when the combination
    // could not be rendered), the metrics past a failing bound and those past a warning bound
    // only, in the metric table's order.
    std::optional<Status> status;
    std::vector<std::string> failed;
    std::vector<std::string> warned;

    // "ssss.enabled=true, shadow_map.resolution=256": keys without their section.
    std::string label() const;
};

struct SweepReport {
    std::string scene;      // scene name
    std::string sceneFile;  // as given
    // "realtime": real-time renders against the reference; "raymarch": reference renders
    // against a tight reference (the raymarcher's own convergence).
    std::string mode = "realtime";
    std::string testRenderer = "realtime";  // what was timed
    std::string referenceDescription;    // "raymarch (scene settings)", "raymarch, root_tolerance
                                         // 1e-07, spp 16"
    std::vector<std::string> keys;       // the varied keys, in --vary order
    std::string metric = "beauty.flip";  // the chart's y
    int frames = 5;                      // frames per combination (median)
    // A sequence scene: each combination rendered each of the sequence's `frames` frames once,
    // each a new particle set; its metrics summarise them (report/sequence_summary.h).
    bool sequence = false;
    std::size_t combinations = 0;  // size of the whole product (all shards)
    std::string createdAt;
    std::string commandLine;
    std::string thresholdsFile;  // as given; empty: the rows were not checked
    std::vector<SweepRow> rows;  // by index
};

// The verdict of a row from its checks (compare::evaluate) and its error: status, failed,
// warned.
void recordChecks(SweepRow& row, const std::vector<Check>& checks);

// The verdict of a sweep held to thresholds: the best row's (a sweep looks for a combination
// that passes); Fail when it has no rows.
Status sweepStatus(const SweepReport& sweep);

// The row of status `atWorst` or better with the lowest median total time ("cheapest");
// nullptr when there is none. Rows without a status or a finite time take no part.
const SweepRow* cheapestRow(const SweepReport& sweep, Status atWorst = Status::Pass);

// The row's varied settings as the arguments that give them to `run` or `render`:
// "--set realtime.ssss.radius_scale=0.6 --set realtime.shadow_map.resolution=1024", each
// quoted for a POSIX shell where it needs it.
std::string setArguments(const SweepRow& row);

// Why no row passes, from the rows' failed and warned metrics, most frequent first:
// "normal.mean_deg failed in 6 of 6 combinations, beauty.flip failed in 2, ...".
std::string whyNonePasses(const SweepReport& sweep);

// The lines a sweep held to thresholds ends with: "cheapest passing: 3.20 ms: --set ..."; or,
// when none passes, "no combination passes: <whyNonePasses>" and, when some only warn,
// "cheapest with warnings only: ...". Empty without thresholds.
std::vector<std::string> verdictLines(const SweepReport& sweep);

// The chart's y for a metric and whether lower is better (the metric table's direction): the
// value itself, or for a metric whose best value is a target (smoothness.ratio: 1) the
// distance |value - target|, lower being better. `label` gets the axis title.
double chartValue(const std::string& metric, double value, std::string* label = nullptr);
bool lowerIsBetter(const std::string& metric);

nlohmann::json sweepJson(const SweepReport& sweep);
// Throws core::InputError naming `source` for anything sweepJson does not write.
SweepReport sweepFromJson(const nlohmann::json& json, const std::string& source);

// One header line, one line per row: index, the varied keys, time.<stage>_ms (total first),
// every metric (in the metric table's order), dir, error. Numbers at full precision; empty for
// a missing value, "nan"/"inf" for non-finite ones.
std::string sweepCsv(const SweepReport& sweep);

// How a combination's time was taken: "median of 5 frames", or for a sequence "median of its
// 3 frames, each a new particle set".
std::string framesDescription(const SweepReport& sweep);

// The chart: x the median total time, y the sweep's metric (chartValue).
std::string sweepSvg(const SweepReport& sweep);

// The page: chart (sweep.svg beside it), the rows, the command line.
std::string sweepHtml(const SweepReport& sweep);

// DIR/sweep.json, sweep.csv, sweep.svg, index.html (atomically).
void writeSweepReport(const SweepReport& sweep, const std::filesystem::path& dir);

}  // namespace twinrender::report
