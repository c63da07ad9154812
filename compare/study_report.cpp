#include "compare/study_report.h"

#include <fmt/format.h>

#include <cmath>
#include <set>

#include "compare/csv.h"
#include "compare/html_page.h"
#include "compare/json_number.h"
#include "compare/markup.h"
#include "compare/metric_table.h"
#include "core/image_io.h"

namespace twinrender::compare {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Every key of the rows' maps with `first` (those present) in front, the others sorted by
// name, or in the metric table's order when `metrics`.
template <typename Get>
std::vector<std::string> columnsOf(const StudyResult& s, Get get,
                                   const std::vector<std::string>& first, bool metrics) {
    std::set<std::string> all;
    for (const StudyRow& r : s.rows)
        for (const auto& [k, v] : get(r)) all.insert(k);
    std::vector<std::string> cols;
    for (const auto& k : first)
        if (all.erase(k)) cols.push_back(k);
    std::vector<std::string> rest(all.begin(), all.end());
    if (metrics) rest = inMetricOrder(std::move(rest));
    cols.insert(cols.end(), rest.begin(), rest.end());
    return cols;
}

std::string xText(double x) {
    if (!std::isfinite(x)) return formatValue(x);
    if (x != 0.0 && (std::abs(x) >= 1e5 || std::abs(x) < 1e-3)) return fmt::format("{:.0e}", x);
    return fmt::format("{:.4g}", x);
}

json studySummaryJson(const StudyResult& s) {
    return {{"name", s.name},
            {"title", s.title},
            {"question", s.question},
            {"scene_file", s.sceneFile},
            {"x_label", s.xLabel},
            {"x_log", s.xLog},
            {"metric", s.metric},
            {"finding", s.finding},
            {"facts", s.facts},
            {"unbracketed_rays", jsonNumber(s.unbracketedRays)},
            {"references", s.references},
            {"points", s.rows.size()},
            {"wall_s", jsonNumber(s.wallSeconds)}};
}

}  // namespace

json studyJson(const StudyResult& s) {
    json j = studySummaryJson(s);
    j["format"] = "twinrender-study";
    j["version"] = 1;
    json rows = json::array();
    for (const StudyRow& r : s.rows) {
        json row = {{"series", r.series},
                    {"x", jsonNumber(r.x)},
                    {"sets", r.sets},
                    {"metrics", numbersJson(r.metrics)},
                    {"timings_ms", numbersJson(r.timingsMs)},
                    {"reference_ms", jsonNumber(r.referenceMs)},
                    {"reference_key", r.referenceKey},
                    {"images", r.images}};
        if (!r.error.empty()) row["error"] = r.error;
        rows.push_back(std::move(row));
    }
    j["rows"] = std::move(rows);
    return j;
}

std::string studyCsv(const StudyResult& s) {
    const auto stages = columnsOf(
        s, [](const StudyRow& r) -> const auto& { return r.timingsMs; },
        {"total", "shadow", "gbuffer", "ssss", "shade", "post"}, false);
    const auto metrics = columnsOf(
        s, [](const StudyRow& r) -> const auto& { return r.metrics; }, s.columns, true);
    std::string out = "series,x,sets";
    auto field = [&](const std::string& text) {
        out += ',';
        out += text;
    };
    for (const auto& st : stages) field(csvField("time." + st + "_ms"));
    field("reference_ms");
    for (const auto& m : metrics) field(csvField(m));
    field("error");
    out += '\n';
    for (const StudyRow& r : s.rows) {
        std::string sets;
        for (const auto& set : r.sets) sets += (sets.empty() ? "" : ";") + set;
        out += csvField(r.series);
        field(exactValue(r.x));
        field(csvField(sets));
        for (const auto& st : stages) field(csvNumber(r.timingsMs, st));
        field(exactValue(r.referenceMs));
        for (const auto& m : metrics) field(csvNumber(r.metrics, m));
        field(csvField(r.error));
        out += '\n';
    }
    return out;
}

void writeStudy(const StudyResult& s, const fs::path& dir) {
    const fs::path d = dir / s.name;
    fs::create_directories(d);
    core::writeTextFile(d / "study.json", studyJson(s).dump(2) + "\n");
    core::writeTextFile(d / "study.csv", studyCsv(s));
    core::writeTextFile(d / "study.svg", lineSvg(s.chart));
}

namespace {

std::string findingsSection(const std::vector<StudyResult>& studies) {
    std::string h =
        "<section>\n<h2>Findings</h2>\n<table class=\"scenes\">\n<thead><tr><th>Study</th>"
        "<th>Finding</th><th class=\"num\">Unbracketed rays</th></tr></thead>\n<tbody>\n";
    for (const auto& s : studies)
        h += fmt::format(
            "<tr><td><a href=\"#{0}\">{1}</a></td><td>{2}</td><td class=\"num\">{3}</td></tr>\n",
            htmlEscape(s.name), htmlEscape(s.title), htmlEscape(s.finding),
            htmlEscape(formatValue(s.unbracketedRays)));
    return h + "</tbody></table>\n</section>\n";
}

// A point's row: its two renders, series, x, the study's metrics, time and unbracketed rays;
// its error in a row under it.
std::string pointRow(const StudyResult& s, const StudyRow& r, const std::string& base) {
    std::string h = "<tr>";
    for (const char* which : {"realtime", "reference"}) {
        const auto it = r.images.find(which);
        h += it == r.images.end()
                 ? std::string("<td></td>")
                 : fmt::format("<td><img class=\"thumb\" src=\"{}\" alt=\"{} {}\"></td>",
                               base + urlPath(it->second), which, htmlEscape(r.series));
    }
    h += "<td>" + htmlEscape(r.series) + "</td><td class=\"num\">" + htmlEscape(xText(r.x)) +
         "</td>";
    for (const auto& m : s.columns) h += metricValueCell(r.metrics, m, m == s.metric);
    const auto t = r.timingsMs.find("total");
    const auto u = r.metrics.find("count.unbracketed_rays");
    h += "<td class=\"num\">" +
         (t == r.timingsMs.end() ? std::string("—") : fmt::format("{:.1f}", t->second)) +
         "</td><td class=\"num\">" +
         (u == r.metrics.end() ? std::string("—") : htmlEscape(formatValue(u->second))) +
         "</td></tr>\n";
    if (!r.error.empty()) h += errorRow(4 + s.columns.size(), r.error);
    return h;
}

std::string studySection(const StudyResult& s) {
    const std::string base = urlPath(s.name) + "/";
    std::string h =
        fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n", htmlEscape(s.name), htmlEscape(s.title));
    h += "<p class=\"lead\">" + htmlEscape(s.question) + "</p>\n";
    h += "<p><strong>Finding:</strong> " + htmlEscape(s.finding) + "</p>\n";
    h += fmt::format(
        "<p class=\"muted\">Scene <code>{}</code>; {} point{}, {} reference render{} with {} "
        "unbracketed ray{}; {:.1f} s. Data: <a href=\"{}study.csv\">study.csv</a>, <a "
        "href=\"{}study.json\">study.json</a>.</p>\n",
        htmlEscape(s.sceneFile), s.rows.size(), s.rows.size() == 1 ? "" : "s", s.references,
        s.references == 1 ? "" : "s", htmlEscape(formatValue(s.unbracketedRays)),
        s.unbracketedRays == 1.0 ? "" : "s", s.wallSeconds, base, base);
    h += "<img src=\"" + base + "study.svg\" alt=\"" + htmlEscape(s.title) +
         ": chart\" style=\"max-width:100%;height:auto\">\n";
    // The rows fold away: the chart and the finding are the page's reading.
    h += fmt::format("<details>\n<summary>{} point{}: renders and every metric</summary>\n",
                     s.rows.size(), s.rows.size() == 1 ? "" : "s");
    h += "<div class=\"scroll\"><table class=\"scenes\">\n<thead><tr><th>Real-time</th>"
         "<th>Reference</th><th>Series</th><th class=\"num\">" +
         htmlEscape(s.xLabel) + "</th>";
    for (const auto& m : s.columns) h += metricHeaderCell(m);
    h += "<th class=\"num\">Real-time <span class=\"unit\">ms</span></th><th "
         "class=\"num\">Unbracketed</th></tr></thead>\n<tbody>\n";
    for (const StudyRow& r : s.rows) h += pointRow(s, r, base);
    return h + "</tbody></table></div>\n</details>\n</section>\n";
}

}  // namespace

void writeStudiesIndex(const std::vector<StudyResult>& studies, const fs::path& dir,
                       const std::string& createdAt, const std::string& commandLine) {
    const std::string title = "twinrender stability studies";
    double unbracketed = 0.0;
    for (const auto& s : studies) unbracketed += s.unbracketedRays;
    std::vector<std::string> facts = {
        fmt::format("{} stud{}", studies.size(), studies.size() == 1 ? "y" : "ies"),
        fmt::format("reference: {} unbracketed ray{}", formatValue(unbracketed),
                    unbracketed == 1.0 ? "" : "s")};
    if (!createdAt.empty()) facts.push_back(htmlEscape(createdAt));
    facts.push_back("<a href=\"studies.json\">studies.json</a>");
    // The findings first: the page's summary, each linked to its study.
    std::string h = pageHeader(title, std::nullopt, facts) + findingsSection(studies);
    for (const auto& s : studies) h += studySection(s);
    h += "</main>\n";
    fs::create_directories(dir);
    json all = json::array();
    for (const auto& s : studies) all.push_back(studySummaryJson(s));
    core::writeTextFile(dir / "studies.json", json({{"format", "twinrender-studies"},
                                                    {"version", 1},
                                                    {"created", createdAt},
                                                    {"command", commandLine},
                                                    {"studies", all}})
                                                      .dump(2) +
                                                  "\n");
    core::writeTextFile(dir / "index.html", reportPage(title, h, createdAt, commandLine));
}

}  // namespace twinrender::compare
