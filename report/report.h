// What a run leaves for people and for CI (docs/cli.md; docs/design.md,
// "Thresholds and baselines"): per-scene metrics.json, summary.json, summary.md, JUnit XML, and an
// HTML report that works offline (one folder, no network: CSS and JavaScript inline, images as
// files beside it).
//
// This header holds the report's data; its files are written by report_json.h (metrics.json,
// summary.json, and the scene reports `merge` reads back), report_markdown.h (summary.md),
// junit.h and report_html.h.
//
// Report layout (writeHtmlReport): DIR/index.html, one row per scene; DIR/<scene>/index.html,
// the scene page. Image paths in SceneReport are relative to DIR/<scene>/, where the renders
// and metrics.json of a scene live.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "compare/error_maps.h"
#include "compare/thresholds.h"

namespace twinrender::report {

using compare::Check;
using compare::ErrorMapImage;
using compare::MetricValues;
using compare::Status;

// One renderer's part of a scene: "realtime" or "raymarch" (the reference).
struct RendererReport {
    std::map<std::string, double> timingsMs;    // "total" and one entry per stage, ms
    std::string device;                         // GL_RENDERER, or the CPU
    std::map<std::string, double> counters;     // e.g. "unbracketed_rays"
    std::map<std::string, std::string> images;  // buffer ("beauty", "normal", ...) -> PNG path
};

// One frame of a sequence scene: every metric of its pair, its times (time.<renderer>_ms) and
// its change from the previous frame (temporal.*, from the second frame on;
// compare/temporal_error.h).
struct SequenceFrame {
    std::int64_t frame = 0;  // the frame number
    MetricValues metrics;
    // The metrics that do not apply to this frame's pair, with why (SceneReport::notApplicable).
    std::map<std::string, std::string> notApplicable;
};

// What a sequence scene adds to its report: the frames, the charts of every metric over them
// and the side-by-side video. Paths are relative to the scene folder.
struct SequenceReport {
    double fps = 24.0;
    std::vector<SequenceFrame> frames;
    // The frame whose buffers and error maps the scene page shows (the worst beauty.flip).
    std::int64_t shownFrame = 0;
    std::map<std::string, std::string> videos;  // MIME type ("video/webm") -> file
    std::map<std::string, std::string> charts;  // metric -> SVG over the frames
};

// One of several renderers a run measures against the same reference (`run --test A --test B`):
// its results beside the others'.
struct TestRendererReport {
    std::string name;  // as --test names it: "realtime", "external", "images"
    MetricValues metrics{};
    std::vector<std::string> notProvided{};  // as SceneReport::notProvided
    std::vector<Check> checks{};             // its own checks, by the metrics' own keys
    std::string error{};                     // set when it could not render or be compared
    // Its times, device and images (paths relative to the scene folder).
    RendererReport render{};
};

struct SceneReport {
    std::string name;         // scene name: the folder name DIR/<name>/
    std::string description;  // one line from the scene file; may be empty
    MetricValues metrics;
    // Threshold and baseline checks together (evaluate() + compareToBaseline()).
    std::vector<Check> checks;
    // The metrics the test image's channels cannot give (compare::MetricResult::notProvided):
    // shown as "not provided", never checked.
    std::vector<std::string> notProvided;
    // The metrics that do not apply to the scene, with why (compare::MetricResult::
    // notApplicable: no occlusion, no emission in either render): shown as "n/a", never checked.
    std::map<std::string, std::string> notApplicable;
    // The blessed metrics of this scene, to show deltas of every metric, also the unchecked
    // ones (times); empty without a baseline.
    MetricValues baseline;
    std::map<std::string, RendererReport> renderers;  // "realtime", "raymarch"
    // Buffer -> error map shown beside the two renders; "beauty" is the ꟻLIP map.
    std::map<std::string, ErrorMapImage> errorMaps;
    nlohmann::json settings;  // the settings used, by dotted key or nested objects
    // Set when the scene could not be rendered or compared; the scene then fails.
    std::string error;
    // Set for a sequence scene: its metrics above then summarise the frames
    // (report/sequence_summary.h).
    std::optional<SequenceReport> sequence;
    // With several test renderers, each one's results in --test order, the first the scene's
    // own (the metrics, renderers and images above); empty with one. The checks of the others
    // that did not pass, and their errors, are in `checks` too, as "<name>:<metric>" (and
    // "<name>:render"), so the verdict, JUnit and summary.md count them.
    std::vector<TestRendererReport> tests;

    // Fail when error is set, else the worst check.
    Status status() const;
};

struct RunReport {
    std::string title = "twinrender report";
    std::string createdAt;    // shown as given ("2024-05-01 12:00 UTC"); may be empty
    std::string commandLine;  // how to reproduce the run; may be empty
    std::string thresholdsFile;
    std::string baselineFile;
    std::vector<SceneReport> scenes;
    // Pages beside the report shown in the index's header: {text, relative URL}, e.g.
    // {"stability studies", "studies/index.html"}.
    std::vector<std::pair<std::string, std::string>> links;

    Status status() const;  // the worst scene; Pass when there are none
};

// Everything of a run in DIR: summary.json, summary.md, DIR/<scene>/metrics.json, the HTML
// pages.
void writeReport(const RunReport& run, const std::filesystem::path& dir);

}  // namespace twinrender::report
