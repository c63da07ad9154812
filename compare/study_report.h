// What `twinrender study` leaves (docs/studies.md): per study a folder with the rows (one per
// rendered setting: its series, its x, every metric, the times, the reference's count of
// unbracketed rays), the chart of one metric against x per series, and a one-line finding
// computed from the rows; and one page for all studies.
//
// DIR/<study>/study.json:
//   {"format": "twinrender-study", "version": 1, "name", "title", "question", "scene_file",
//    "x_label", "x_log", "metric", "finding", "facts": {...}, "unbracketed_rays",
//    "references", "wall_s", "rows": [{"series", "x", "sets": [...], "metrics": {...},
//    "timings_ms": {...}, "reference_ms", "reference_key", "images": {...}, ["error"]}]}
// DIR/<study>/study.csv, study.svg; DIR/studies.json (every study without its rows) and
// DIR/index.html. Non-finite numbers as json_number.h writes them.
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "compare/svg_chart.h"
#include "compare/thresholds.h"

namespace twinrender::compare {

struct StudyRow {
    std::string series;             // "standard depth", "SSSS on"
    double x = 0.0;                 // the study's x (far/near, pixels per particle, degrees, ...)
    std::vector<std::string> sets;  // the KEY=VALUE overrides that made this point
    MetricValues metrics;           // against the reference; count.unbracketed_rays its failures
    std::map<std::string, double> timingsMs;    // the real-time frame: "total" and per stage
    double referenceMs = 0.0;                   // the reference's render time (or cached time)
    std::string referenceKey;                   // its cache key
    std::map<std::string, std::string> images;  // "realtime", "reference" -> PNG, relative
    std::string error;                          // set when the point could not be rendered
};

struct StudyResult {
    std::string name;      // "depth_range": the folder name
    std::string title;     // "Depth range"
    std::string question;  // what the study asks, one sentence
    std::string sceneFile;
    std::string xLabel;  // with its unit
    bool xLog = false;
    std::string metric;                               // the chart's y
    std::vector<std::string> columns;                 // metrics shown in the page's table, in order
    std::string finding;                              // one line, computed from the rows
    nlohmann::json facts = nlohmann::json::object();  // the numbers the finding states
    LineChart chart;                                  // built from the rows
    double unbracketedRays = 0.0;                     // over the distinct references
    std::size_t references = 0;                       // distinct references rendered or read
    double wallSeconds = 0.0;
    std::vector<StudyRow> rows;
};

nlohmann::json studyJson(const StudyResult& study);
// series, x, the overrides (one column, ";"-joined), time.<stage>_ms, reference_ms, every
// metric (the study's columns first, then the metric table's order), error. Numbers at full
// precision.
std::string studyCsv(const StudyResult& study);

// DIR/<name>/study.json, study.csv, study.svg (atomically).
void writeStudy(const StudyResult& study, const std::filesystem::path& dir);

// DIR/index.html (every study: finding, chart, table, thumbnails) and DIR/studies.json.
void writeStudiesIndex(const std::vector<StudyResult>& studies, const std::filesystem::path& dir,
                       const std::string& createdAt, const std::string& commandLine);

}  // namespace twinrender::compare
