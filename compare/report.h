// What a run leaves for people and for CI (DESIGN.md, "Command line" and "Thresholds and
// baselines"): per-scene metrics.json, summary.json, JUnit XML, and an HTML report that works
// offline (one folder, no network: CSS and JavaScript inline, images as files beside it).
//
// Report layout (writeHtmlReport): DIR/index.html, one row per scene; DIR/<scene>/index.html,
// the scene page. Image paths in SceneReport are relative to DIR/<scene>/, where the renders
// and metrics.json of a scene live.
//
// JSON has no infinity or NaN: such metric values are written as the strings "Infinity",
// "-Infinity" and "NaN" (jsonNumber); numberFromJson reads them back.
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "compare/thresholds.h"
#include "core/image.h"

namespace twinrender::compare {

// ---- Input data ------------------------------------------------------------------------

// A colour-mapped error image and the range its colours span.
struct ErrorMapImage {
    std::string path;   // PNG, relative to the scene folder
    std::string label;  // "ꟻLIP error", "normal error"
    double lo = 0.0;    // value at the dark end of the colour map
    double hi = 1.0;    // value at the bright end
    std::string unit;   // "" for unitless, "°", "px"
};

// One renderer's part of a scene: "realtime" or "raymarch" (the reference).
struct RendererReport {
    std::map<std::string, double> timingsMs;    // "total" and one entry per stage, ms
    std::string device;                         // GL_RENDERER, or the CPU
    std::map<std::string, double> counters;     // e.g. "unbracketed_rays"
    std::map<std::string, std::string> images;  // buffer ("beauty", "normal", ...) -> PNG path
};

struct SceneReport {
    std::string name;         // scene name: the folder name DIR/<name>/
    std::string description;  // one line from the scene file; may be empty
    MetricValues metrics;
    // Threshold and baseline checks together (evaluate() + compareToBaseline()).
    std::vector<Check> checks;
    // The blessed metrics of this scene, to show deltas of every metric, also the unchecked
    // ones (times); empty without a baseline.
    MetricValues baseline;
    std::map<std::string, RendererReport> renderers;  // "realtime", "raymarch"
    // Buffer -> error map shown beside the two renders; "beauty" is the ꟻLIP map.
    std::map<std::string, ErrorMapImage> errorMaps;
    nlohmann::json settings;  // the settings used, by dotted key or nested objects
    // Set when the scene could not be rendered or compared; the scene then fails.
    std::string error;

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

// ---- JSON and JUnit --------------------------------------------------------------------

// A number, or "Infinity", "-Infinity", "NaN" for the values JSON cannot hold.
nlohmann::json jsonNumber(double value);
// A number or one of those strings; nullopt for anything else.
std::optional<double> numberFromJson(const nlohmann::json& value);

// {"scene", "description", "status", "metrics": {key: value}, "checks": [{"metric", "value",
//  "bound", "limit", "status", "message", ["baseline", "delta"]}], ["error"]}
nlohmann::json metricsJson(const SceneReport& scene);
// {"status", "scenes": [{"name", "status", "metrics", "timings_ms": {renderer: {stage: ms}},
//  "checks", "settings", ["error"]}], "thresholds", "baseline", "created"}
nlohmann::json summaryJson(const RunReport& run);
// One <testsuite>, one <testcase> per scene and checked metric (classname "twinrender.SCENE",
// name METRIC) with the value and every bound as <property>; a <failure message=...> when a
// check fails, the warnings in <system-out>. A scene that could not be rendered is one
// testcase "render" with an <error>; a scene without checks one passing testcase "render".
std::string junitXml(const RunReport& run);

// Atomic writes (temporary name, then rename).
void writeMetricsJson(const SceneReport& scene, const std::filesystem::path& file);
void writeSummaryJson(const RunReport& run, const std::filesystem::path& file);
void writeJunit(const RunReport& run, const std::filesystem::path& file);

// ---- HTML ------------------------------------------------------------------------------

// Writes DIR/index.html and DIR/<scene>/index.html for every scene (atomically). The images
// named in the reports must already be in place (the pages only link to them). Every page
// carries a self-test: it records script errors, console.error calls and images that fail to
// load into <pre id="selftest">, which reads "selftest: ok" once the page has loaded without
// any, or "selftest: FAIL" and one line per problem (tests/report_browser_test.cpp).
void writeHtmlReport(const RunReport& run, const std::filesystem::path& dir);

// Everything of a run in DIR: summary.json, DIR/<scene>/metrics.json, the HTML pages.
void writeReport(const RunReport& run, const std::filesystem::path& dir);

// ---- Images for the report -------------------------------------------------------------

// The buffers a scene page can switch between, in its order:
// beauty, normal, uv, depth, id, shadow, emission.
const std::vector<std::string>& bufferNames();

struct BufferVisualSettings {
    float exposure = 1.0f;  // for beauty and emission, as the scene's camera.exposure, > 0
    // Depth range (scene units, 0 < near < far) mapped log-scaled from white (near) to dark
    // grey (far). Both renders of a scene must share it (depthRange of both) so equal
    // depths look equal; {0, 0}: the image's own range.
    std::pair<double, double> depthRange{0.0, 0.0};
};

// The smallest and largest finite positive depth (channel Z, covered pixels) over both
// images; {0, 0} when neither has any.
std::pair<double, double> depthRange(const core::Image& a, const core::Image& b);

// An R, G, B display image in [0, 1] of one buffer of an AOV image (channel names of
// DESIGN.md): beauty -> tonemapped R,G,B; normal -> 0.5 + 0.5 n; uv -> (u, v, 0); depth ->
// log-scaled grey; id -> one distinct colour per body (the same in every image); shadow ->
// white lit, grey occluded; emission -> tonemapped. Pixels without coverage (A = 0, or
// Z = inf without A) are a dark slate, except for beauty. Throws core::NotComparableError
// naming the channel when the image lacks one the buffer needs; std::invalid_argument for an
// unknown buffer.
core::Image visualiseBuffer(const core::Image& aov, std::string_view buffer,
                            const BufferVisualSettings& settings = {});

// Writes DIR/<stem>.<buffer>.png for every buffer of bufferNames() whose channels the AOV
// image has and returns buffer -> file name (relative to DIR), ready for
// RendererReport::images. `beautyDisplay` (R, G, B in [0, 1], e.g. the renderer's own PNG
// with bloom) replaces the tonemapped beauty when given.
std::map<std::string, std::string> writeBufferImages(const core::Image& aov,
                                                     const core::Image* beautyDisplay,
                                                     const std::filesystem::path& dir,
                                                     const std::string& stem,
                                                     const BufferVisualSettings& settings = {});

// The magma colour map (matplotlib's, CC0, perceptually uniform): t in [0, 1] -> sRGB display
// value in [0, 1]; t is clamped.
void magma(double t, float rgb[3]);
// Channel `channel` of `map` mapped from [lo, hi] through magma; NaN pixels are black.
core::Image colourMapped(const core::Image& map, int channel, double lo, double hi);
// colourMapped(...) written as PNG (atomically).
void writeErrorMapPng(const core::Image& map, int channel, double lo, double hi,
                      const std::filesystem::path& png);

// Writes the per-pixel error maps of compare::computeMetrics (MetricResult::errorMaps, keys
// "beauty.flip", "normal", "depth", "uv", "id", "shadow", "emission"; one channel each) as
// DIR/<stem>.<buffer>.png through magma, each over a fixed range so that scenes and runs can
// be compared by eye: ꟻLIP 0..1, normal 0..30°, depth 0..0.1 (relative), uv 0..0.05, id 0..1
// (1: another body), shadow 0..2 (1: false shadow, 2: missed shadow); emission and unknown
// keys 0..their maximum. Returns buffer -> ErrorMapImage ("beauty.flip" becomes "beauty"),
// ready for SceneReport::errorMaps.
std::map<std::string, ErrorMapImage> writeErrorMapImages(
    const std::map<std::string, core::Image>& errorMaps, const std::filesystem::path& dir,
    const std::string& stem = "error");

// Unit of a metric for tables ("dB", "°", "px", "ms"; "" for ratios and fractions).
std::string metricUnit(std::string_view metric);


// ---- Shared with other reports and with `merge` -----------------------------------------

// Every field of a scene's report as JSON (metricsJson's keys plus "baseline", "renderers"
// with timings, device, counters and images, "error_maps" and "settings"), and back:
// sceneReportFromJson(sceneReportJson(s)) reproduces s, so shards of a run can be merged into
// the report one run writes. Throws core::InputError naming `source` for malformed JSON.
nlohmann::json sceneReportJson(const SceneReport& scene);
SceneReport sceneReportFromJson(const nlohmann::json& json, const std::string& source);

// "pass" | "warn" | "fail" -> Status; nullopt for anything else.
std::optional<Status> statusFromString(std::string_view text);

// A page in the report's style and with its self-test (writeHtmlReport): head, `body`
// (everything inside <body> above the footer, e.g. a <header class="top"> and a <main>), and
// the footer with `createdAt` and `commandLine` (either may be empty).
std::string reportPage(const std::string& title, const std::string& body,
                       const std::string& createdAt, const std::string& commandLine);
// Text for HTML (&, <, >, ", ' escaped) and a relative path as a URL (percent-encoded).
std::string htmlEscape(std::string_view text);
// Text for XML (JUnit, SVG): & < > escaped, and " too inside attributes (`attribute`), where
// newlines and tabs become character references; other control characters, which XML 1.0
// does not allow, become spaces.
std::string xmlEscape(std::string_view text, bool attribute);
std::string urlPath(std::string_view path);

}  // namespace twinrender::compare
