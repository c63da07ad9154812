// What `twinrender study` leaves (docs/studies.md): per study a folder with the rows (one per
// rendered setting: its series, its x, every metric, the times, the reference's count of
// unbracketed rays), the chart of one metric against x per series, and a one-line finding
// computed from the rows; and one page for all studies.
//
// DIR/<study>/study.json:
//   {"format": "twinrender-study", "version": 1, "name", "title", "question", "scene_file",
//    "x_label", "x_log", "metric", "finding", "facts": {...}, "unbracketed_rays",
//    "references", "wall_s", ["tables": [{"file", "caption", "labels": [...],
//    "columns": [...], "lines": [{"labels": [...], "values": {...}}]}]],
//    "rows": [{["scene"], "series", "x", "sets": [...], "metrics": {...},
//    "timings_ms": {...}, "reference_ms", "reference_key", "images": {...}, ["error"]}]}
// DIR/<study>/study.csv, study.svg; DIR/studies.json (every study without its rows) and
// DIR/index.html. Non-finite numbers as json_number.h writes them. A study whose points span
// several scenes has a "scene" in each row (and a first CSV column); a study with tables or
// figures also writes them (<file>.csv, <file>.svg) and study.md, its finding, charts and
// tables as a Markdown section for a page to include.
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "compare/thresholds.h"
#include "report/svg_chart.h"

namespace twinrender::report {

using compare::MetricValues;

struct StudyRow {
    std::string scene;              // the point's scene when the study spans several; else ""
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

// A table computed from the rows (the methods study: a line per method, parameter and shape
// with the medians over the default scenes).
struct StudyTable {
    std::string file;                  // "summary": DIR/<study>/summary.csv
    std::string caption;               // what a line is and how its values are taken
    std::vector<std::string> labels;   // the headers of the text columns: "method", "shape"
    std::vector<std::string> columns;  // the number columns: metric keys (compare's table, with
                                       // its unit and meaning) or other names (a scene's)
    struct Line {
        std::vector<std::string> labels;  // one per label column
        std::map<std::string, double> values;
    };
    std::vector<Line> lines;
};

// A chart beyond the study's own (the methods study: the methods along particle size).
struct StudyFigure {
    std::string file;     // "particle_size": DIR/<study>/particle_size.svg
    std::string caption;  // what it shows, one sentence
    LineChart chart;
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
    // When set, study.svg is this chart instead: the cost of each setting against its error,
    // the Pareto front drawn (the methods study).
    std::optional<ScatterChart> scatter;
    std::vector<StudyFigure> figures;
    std::vector<StudyTable> tables;
    double unbracketedRays = 0.0;  // over the distinct references
    std::size_t references = 0;    // distinct references rendered or read
    double wallSeconds = 0.0;
    std::vector<StudyRow> rows;
};

// The metric's bounds as a chart's horizontal marks (LineChart::yMarks): "max 0.05",
// "warn_max 0.03"; none for a metric `bounds` does not hold. The studies' and the sequences'
// charts draw them.
std::vector<std::pair<double, std::string>> boundMarks(const compare::Bounds& bounds,
                                                       const std::string& metric);

nlohmann::json studyJson(const StudyResult& study);
// [scene,] series, x, the overrides (one column, ";"-joined), time.<stage>_ms, reference_ms,
// every metric (the study's columns first, then the metric table's order), error. Numbers at
// full precision.
std::string studyCsv(const StudyResult& study);
// The label columns, then the number columns at full precision.
std::string tableCsv(const StudyTable& table);
// The study's title as a heading of `level`, its finding, its charts (linked by file name:
// study.svg, <figure>.svg), and its tables, numbers as formatValue writes them.
std::string studyMarkdown(const StudyResult& study, int level);

// DIR/<name>/study.json, study.csv, study.svg, and the figures, tables and study.md of a study
// that has them (atomically).
void writeStudy(const StudyResult& study, const std::filesystem::path& dir);

// DIR/index.html (every study: finding, chart, table, thumbnails) and DIR/studies.json.
// `quick`: the studies ran in their quick form (fewer points and particles), which the page
// says beside each finding, pointing at the published ones (docs/studies.md). `back`: the
// relative URL of the report the studies belong to ("../index.html"), linked from the header;
// "" for none.
void writeStudiesIndex(const std::vector<StudyResult>& studies, const std::filesystem::path& dir,
                       const std::string& createdAt, const std::string& commandLine,
                       bool quick = false, const std::string& back = "");

}  // namespace twinrender::report
