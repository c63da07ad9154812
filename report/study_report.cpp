#include "report/study_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "compare/json_number.h"
#include "compare/metric_table.h"
#include "core/image_io.h"
#include "core/stage_table.h"
#include "core/write_roots.h"
#include "report/csv.h"
#include "report/html_page.h"
#include "report/markup.h"
#include "report/published_findings.h"

namespace twinrender::report {

using compare::exactValue;
using compare::findMetric;
using compare::formatValue;
using compare::inMetricOrder;
using compare::jsonNumber;
using compare::metricUnit;
using compare::numbersJson;

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
    rest = metrics ? inMetricOrder(std::move(rest)) : core::inStageOrder(std::move(rest));
    cols.insert(cols.end(), rest.begin(), rest.end());
    return cols;
}

std::string xText(double x) {
    if (!std::isfinite(x)) return formatValue(x);
    if (x != 0.0 && (std::abs(x) >= 1e5 || std::abs(x) < 1e-3)) return fmt::format("{:.0e}", x);
    return fmt::format("{:.4g}", x);
}

bool spansScenes(const StudyResult& s) {
    for (const StudyRow& r : s.rows)
        if (!r.scene.empty()) return true;
    return false;
}

json tableJson(const StudyTable& t) {
    json lines = json::array();
    for (const auto& line : t.lines)
        lines.push_back({{"labels", line.labels}, {"values", numbersJson(line.values)}});
    return {{"file", t.file},
            {"caption", t.caption},
            {"labels", t.labels},
            {"columns", t.columns},
            {"lines", lines}};
}

// A number column's header: a metric with its unit, or the name as given.
std::string columnTitle(const std::string& column) {
    if (!findMetric(column)) return column;
    const std::string unit = metricUnit(column);
    return unit.empty() ? column : column + " (" + unit + ")";
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

std::vector<std::pair<double, std::string>> boundMarks(const compare::Bounds& bounds,
                                                       const std::string& metric) {
    std::vector<std::pair<double, std::string>> marks;
    const auto it = bounds.find(metric);
    if (it == bounds.end()) return marks;
    const compare::MetricBounds& b = it->second;
    for (const auto& [limit, name] :
         {std::pair{&b.max, "max"}, std::pair{&b.min, "min"}, std::pair{&b.warnMax, "warn_max"},
          std::pair{&b.warnMin, "warn_min"}})
        if (*limit)
            marks.emplace_back((*limit)->value,
                               fmt::format("{} {}", name, formatValue((*limit)->value)));
    return marks;
}

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
        if (!r.scene.empty()) row["scene"] = r.scene;
        if (!r.error.empty()) row["error"] = r.error;
        rows.push_back(std::move(row));
    }
    if (!s.tables.empty()) {
        j["tables"] = json::array();
        for (const StudyTable& t : s.tables) j["tables"].push_back(tableJson(t));
    }
    j["rows"] = std::move(rows);
    return j;
}

std::string studyCsv(const StudyResult& s) {
    const auto stages = columnsOf(
        s, [](const StudyRow& r) -> const auto& { return r.timingsMs; }, {}, false);
    const auto metrics = columnsOf(
        s, [](const StudyRow& r) -> const auto& { return r.metrics; }, s.columns, true);
    const bool scenes = spansScenes(s);
    std::string out = scenes ? "scene,series,x,sets" : "series,x,sets";
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
        if (scenes) {
            out += csvField(r.scene);
            field(csvField(r.series));
        } else {
            out += csvField(r.series);
        }
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

std::string tableCsv(const StudyTable& t) {
    auto line = [](const std::vector<std::string>& fields) {
        std::string out;
        for (std::size_t i = 0; i < fields.size(); ++i) out += (i ? "," : "") + fields[i];
        return out + "\n";
    };
    std::vector<std::string> header;
    for (const auto& l : t.labels) header.push_back(csvField(l));
    for (const auto& c : t.columns) header.push_back(csvField(c));
    std::string out = line(header);
    for (const auto& l : t.lines) {
        std::vector<std::string> fields;
        for (std::size_t i = 0; i < t.labels.size(); ++i)
            fields.push_back(csvField(i < l.labels.size() ? l.labels[i] : ""));
        for (const auto& c : t.columns) fields.push_back(csvNumber(l.values, c));
        out += line(fields);
    }
    return out;
}

std::string studyMarkdown(const StudyResult& s, int level) {
    const std::string h(static_cast<std::size_t>(std::max(level, 1)), '#');
    std::string md =
        h + " " + s.title + "\n\n" + s.question + "\n\n**Finding:** " + s.finding + "\n\n";
    md += "![" + (s.scatter ? s.scatter->title : s.chart.title) + "](study.svg)\n\n";
    for (const StudyFigure& f : s.figures)
        md += "![" + f.chart.title + "](" + f.file + ".svg)\n\n*" + f.caption + "*\n\n";
    // One cell: " text |"; a bar in the text is escaped (Markdown table cells cannot hold one).
    auto cell = [&md](std::string_view text) {
        md += ' ';
        for (char c : text) {
            if (c == '|') md += '\\';
            md += c;
        }
        md += " |";
    };
    for (const StudyTable& t : s.tables) {
        md += "*" + t.caption + "*\n\n|";
        for (const auto& l : t.labels) cell(l);
        for (const auto& c : t.columns) cell(columnTitle(c));
        md += "\n|";
        for (std::size_t i = 0; i < t.labels.size(); ++i) md += " --- |";
        for (std::size_t i = 0; i < t.columns.size(); ++i) md += " ---: |";
        md += "\n";
        for (const auto& line : t.lines) {
            md += "|";
            for (std::size_t i = 0; i < t.labels.size(); ++i)
                cell(i < line.labels.size() ? line.labels[i] : "");
            for (const auto& c : t.columns) {
                const auto it = line.values.find(c);
                cell(it == line.values.end() ? "—" : formatValue(it->second));
            }
            md += "\n";
        }
        md += "\n";
    }
    return md;
}

void writeStudy(const StudyResult& s, const fs::path& dir) {
    const fs::path d = dir / s.name;
    core::makeFolders(d);
    core::writeTextFile(d / "study.json", studyJson(s).dump(2) + "\n");
    core::writeTextFile(d / "study.csv", studyCsv(s));
    core::writeTextFile(d / "study.svg", s.scatter ? scatterSvg(*s.scatter) : lineSvg(s.chart));
    for (const StudyFigure& f : s.figures)
        core::writeTextFile(d / (f.file + ".svg"), lineSvg(f.chart));
    for (const StudyTable& t : s.tables) core::writeTextFile(d / (t.file + ".csv"), tableCsv(t));
    if (!s.figures.empty() || !s.tables.empty() || s.scatter)
        core::writeTextFile(d / "study.md", studyMarkdown(s, 2));
}

namespace {

// What a quick run's finding is, beside it: not the published figure.
const char* QUICK_NOTE =
    "quick run: fewer points and particles than the published study, so its figures can differ "
    "from the published ones (under it)";

std::string quickLabel(bool quick) {
    return quick ? fmt::format("<span class=\"badge warn\" title=\"{}\">quick run</span> ",
                               htmlEscape(QUICK_NOTE))
                 : "";
}

// A quick run's finding is followed by the published one (docs/findings.json), the full
// study's, and where the docs show it; nothing for a full run or a study the docs do not publish.
std::string publishedLine(const StudyResult& s, bool quick) {
    if (!quick) return "";
    const auto p = publishedFinding(s.name);
    if (!p) return "";
    return fmt::format(
        "<div class=\"published muted\"><b>Published</b> (full run{}, <code>{}</code>): "
        "{}</div>",
        p->measured.empty() ? "" : ", " + htmlEscape(p->measured), htmlEscape(p->page),
        htmlEscape(p->finding));
}

std::string findingsSection(const std::vector<StudyResult>& studies, bool quick) {
    std::string h = "<section>\n<h2>Findings</h2>\n";
    if (quick)
        h += "<p class=\"device-note\">These are <b>quick runs</b>: each study renders fewer "
             "points and particles than its published form, so a figure here can differ from "
             "the published one, shown under it with the docs page that holds it; <code>twinrender "
             "study</code> without <code>--quick</code> (or <code>scripts/run --studies "
             "full</code>) reproduces the published figures.</p>\n";
    h += "<table class=\"scenes\">\n<thead><tr><th>Study</th><th>Finding</th><th "
         "class=\"num\">Unbracketed rays</th></tr></thead>\n<tbody>\n";
    for (const auto& s : studies)
        h += fmt::format(
            "<tr><td><a href=\"#{0}\">{1}</a></td><td>{4}{2}{5}</td><td "
            "class=\"num\">{3}</td></tr>\n",
            htmlEscape(s.name), htmlEscape(s.title), htmlEscape(s.finding),
            htmlEscape(formatValue(s.unbracketedRays)), quickLabel(quick), publishedLine(s, quick));
    return h + "</tbody></table>\n</section>\n";
}

// A point's row: its two renders, [scene,] series, x, the study's metrics, time and
// unbracketed rays; its error in a row under it.
std::string pointRow(const StudyResult& s, const StudyRow& r, const std::string& base,
                     bool scenes) {
    std::string h = "<tr>";
    for (const char* which : {"realtime", "reference"}) {
        const auto it = r.images.find(which);
        h += it == r.images.end()
                 ? std::string("<td></td>")
                 : fmt::format("<td><img class=\"thumb\" src=\"{}\" alt=\"{} {}\"></td>",
                               base + urlPath(it->second), which, htmlEscape(r.series));
    }
    if (scenes) h += "<td>" + htmlEscape(r.scene) + "</td>";
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
    if (!r.error.empty()) h += errorRow(4 + (scenes ? 1 : 0) + s.columns.size(), r.error);
    return h;
}

// A study's table: its caption, the label columns, the number columns with their units.
std::string tableSection(const StudyTable& t, const std::string& base) {
    std::string h = "<p>" + htmlEscape(t.caption) +
                    fmt::format(" Data: <a href=\"{}{}.csv\">{}.csv</a>.</p>\n", base,
                                urlPath(t.file), htmlEscape(t.file));
    h += "<div class=\"scroll\"><table class=\"scenes\">\n<thead><tr>";
    for (const auto& l : t.labels) h += "<th>" + htmlEscape(l) + "</th>";
    for (const auto& c : t.columns)
        h += findMetric(c) ? metricHeaderCell(c) : "<th class=\"num\">" + htmlEscape(c) + "</th>";
    h += "</tr></thead>\n<tbody>\n";
    for (const auto& line : t.lines) {
        h += "<tr>";
        for (std::size_t i = 0; i < t.labels.size(); ++i)
            h += "<td>" + htmlEscape(i < line.labels.size() ? line.labels[i] : "") + "</td>";
        for (const auto& c : t.columns) h += metricValueCell(line.values, c, false);
        h += "</tr>\n";
    }
    return h + "</tbody></table></div>\n";
}

std::string studySection(const StudyResult& s, bool quick) {
    const std::string base = urlPath(s.name) + "/";
    std::string h =
        fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n", htmlEscape(s.name), htmlEscape(s.title));
    h += "<p class=\"lead\">" + htmlEscape(s.question) + "</p>\n";
    h += "<p><strong>Finding:</strong> " + quickLabel(quick) + htmlEscape(s.finding) + "</p>\n" +
         publishedLine(s, quick) + "\n";
    h += fmt::format(
        "<p class=\"muted\">Scene <code>{}</code>; {} point{}, {} reference render{} with {} "
        "unbracketed ray{}; {:.1f} s. Data: <a href=\"{}study.csv\">study.csv</a>, <a "
        "href=\"{}study.json\">study.json</a>.</p>\n",
        htmlEscape(s.sceneFile), s.rows.size(), s.rows.size() == 1 ? "" : "s", s.references,
        s.references == 1 ? "" : "s", htmlEscape(formatValue(s.unbracketedRays)),
        s.unbracketedRays == 1.0 ? "" : "s", s.wallSeconds, base, base);
    h += "<img src=\"" + base + "study.svg\" alt=\"" + htmlEscape(s.title) +
         ": chart\" style=\"max-width:100%;height:auto\">\n";
    for (const StudyFigure& f : s.figures)
        h += "<img src=\"" + base + urlPath(f.file) + ".svg\" alt=\"" + htmlEscape(f.chart.title) +
             "\" style=\"max-width:100%;height:auto\">\n<p class=\"muted\">" +
             htmlEscape(f.caption) + "</p>\n";
    for (const StudyTable& t : s.tables) h += tableSection(t, base);
    const bool scenes = spansScenes(s);
    // The rows fold away: the chart and the finding are the page's reading.
    h += fmt::format("<details>\n<summary>{} point{}: renders and every metric</summary>\n",
                     s.rows.size(), s.rows.size() == 1 ? "" : "s");
    h += "<div class=\"scroll\"><table class=\"scenes\">\n<thead><tr><th>Real-time</th>"
         "<th>Reference</th>";
    if (scenes) h += "<th>Scene</th>";
    h += "<th>Series</th><th class=\"num\">" + htmlEscape(s.xLabel) + "</th>";
    for (const auto& m : s.columns) h += metricHeaderCell(m);
    h += "<th class=\"num\">Real-time <span class=\"unit\">ms</span></th><th "
         "class=\"num\">Unbracketed</th></tr></thead>\n<tbody>\n";
    for (const StudyRow& r : s.rows) h += pointRow(s, r, base, scenes);
    return h + "</tbody></table></div>\n</details>\n</section>\n";
}

}  // namespace

void writeStudiesIndex(const std::vector<StudyResult>& studies, const fs::path& dir,
                       const std::string& createdAt, const std::string& commandLine, bool quick,
                       const std::string& back) {
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
    if (quick) facts.push_back("quick run");
    std::string h = pageHeader(title, std::nullopt, facts,
                               back.empty() ? ""
                                            : "<nav class=\"scene-nav\"><a class=\"back\" href=\"" +
                                                  urlPath(back) + "\">← Report</a></nav>") +
                    findingsSection(studies, quick);
    for (const auto& s : studies) h += studySection(s, quick);
    h += "</main>\n";
    core::makeFolders(dir);
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

}  // namespace twinrender::report
