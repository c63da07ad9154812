#include "compare/sweep_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "compare/csv.h"
#include "compare/html_page.h"
#include "compare/json_number.h"
#include "compare/markup.h"
#include "compare/metric_table.h"
#include "compare/svg_chart.h"
#include "compare/thresholds.h"
#include "core/error.h"
#include "core/image_io.h"

namespace twinrender::compare {

namespace fs = std::filesystem;
using nlohmann::json;

std::string SweepRow::label() const {
    std::string s;
    for (const auto& [key, value] : settings) {
        const auto dot = key.find('.');
        const bool section = key.rfind("realtime.", 0) == 0 || key.rfind("raymarch.", 0) == 0;
        s += (s.empty() ? "" : ", ") +
             (section && dot != std::string::npos ? key.substr(dot + 1) : key) + "=" + value;
    }
    return s;
}

double chartValue(const std::string& metric, double value, std::string* label) {
    const MetricInfo* info = findMetric(metric);
    const Better better = info ? info->better : Better::Lower;
    const double origin = info ? info->origin : 0.0;
    const std::string unit = metricUnit(metric);
    const std::string withUnit = unit.empty() ? metric : fmt::format("{} ({})", metric, unit);
    if (better == Better::Closer) {
        if (label)
            *label = fmt::format("|{} − {}| (lower is better)", withUnit, formatValue(origin));
        return std::abs(value - origin);
    }
    if (label)
        *label = fmt::format("{} ({} is better)", withUnit,
                             better == Better::Higher ? "higher" : "lower");
    return value;
}

bool lowerIsBetter(const std::string& metric) {
    const MetricInfo* info = findMetric(metric);
    return !info || info->better != Better::Higher;
}

namespace {

// Every metric of the rows, in the table's order.
std::vector<std::string> metricColumns(const SweepReport& s) {
    std::set<std::string> all;
    for (const SweepRow& r : s.rows)
        for (const auto& [k, v] : r.metrics) all.insert(k);
    return inMetricOrder({all.begin(), all.end()});
}

std::vector<std::string> stageColumns(const SweepReport& s) {
    std::set<std::string> all;
    for (const SweepRow& r : s.rows)
        for (const auto& [k, v] : r.timingsMs) all.insert(k);
    // The total, then the stages in pipeline order (real-time, then raymarcher), then others.
    static const std::vector<std::string> order = {"total",    "cull",  "upload", "shadow",
                                                   "gbuffer",  "ssss",  "shade",  "post",
                                                   "readback", "build", "trace"};
    std::vector<std::string> cols;
    for (const auto& st : order)
        if (all.erase(st)) cols.push_back(st);
    cols.insert(cols.end(), all.begin(), all.end());
    return cols;
}

}  // namespace

json sweepJson(const SweepReport& s) {
    json rows = json::array();
    for (const SweepRow& r : s.rows) {
        json settings = json::object();
        for (const auto& [k, v] : r.settings) settings[k] = v;
        json j = {{"index", r.index},
                  {"label", r.label()},
                  {"dir", r.dir},
                  {"settings", settings},
                  {"timings_ms", numbersJson(r.timingsMs)},
                  {"metrics", numbersJson(r.metrics)},
                  {"reference_key", r.referenceKey}};
        if (!r.error.empty()) j["error"] = r.error;
        rows.push_back(std::move(j));
    }
    return {{"format", "twinrender-sweep"},
            {"version", 1},
            {"scene", s.scene},
            {"scene_file", s.sceneFile},
            {"mode", s.mode},
            {"test", s.testRenderer},
            {"reference", s.referenceDescription},
            {"keys", s.keys},
            {"metric", s.metric},
            {"better", lowerIsBetter(s.metric) ? "lower" : "higher"},
            {"frames", s.frames},
            {"combinations", s.combinations},
            {"created", s.createdAt},
            {"command", s.commandLine},
            {"rows", rows}};
}

SweepReport sweepFromJson(const json& j, const std::string& source) {
    auto bad = [&](const std::string& what) {
        return core::InputError(fmt::format(
            "{}: {} (expected sweep.json as `twinrender sweep` writes it)", source, what));
    };
    auto numbers = [&](const json& obj, const std::string& where) {
        std::map<std::string, double> m;
        for (const auto& [k, v] : obj.items()) {
            const auto n = numberFromJson(v);
            if (!n) throw bad(where + "." + k + " is not a number");
            m[k] = *n;
        }
        return m;
    };
    try {
        if (j.value("format", "") != "twinrender-sweep")
            throw bad("no \"format\": \"twinrender-sweep\"");
        if (j.value("version", 0) != 1) throw bad("unknown version");
        SweepReport s;
        s.scene = j.at("scene").get<std::string>();
        s.sceneFile = j.at("scene_file").get<std::string>();
        s.mode = j.at("mode").get<std::string>();
        s.testRenderer = j.at("test").get<std::string>();
        s.referenceDescription = j.at("reference").get<std::string>();
        s.keys = j.at("keys").get<std::vector<std::string>>();
        s.metric = j.at("metric").get<std::string>();
        s.frames = j.at("frames").get<int>();
        s.combinations = j.at("combinations").get<std::size_t>();
        s.createdAt = j.value("created", "");
        s.commandLine = j.value("command", "");
        for (const json& r : j.at("rows")) {
            SweepRow row;
            row.index = r.at("index").get<std::size_t>();
            row.dir = r.at("dir").get<std::string>();
            for (const std::string& k : s.keys)
                row.settings.emplace_back(k, r.at("settings").at(k).get<std::string>());
            row.timingsMs = numbers(r.at("timings_ms"), "timings_ms");
            row.metrics = numbers(r.at("metrics"), "metrics");
            row.referenceKey = r.value("reference_key", "");
            row.error = r.value("error", "");
            s.rows.push_back(std::move(row));
        }
        return s;
    } catch (const json::exception& e) {
        throw bad(e.what());
    }
}

std::string sweepCsv(const SweepReport& s) {
    const auto stages = stageColumns(s);
    const auto metrics = metricColumns(s);
    std::string out = "index";
    // Appended piece by piece ("," + temporary trips GCC 12's -Wrestrict false positive).
    auto field = [&](const std::string& text) {
        out += ',';
        out += text;
    };
    for (const auto& k : s.keys) field(csvField(k));
    for (const auto& st : stages) field(csvField("time." + st + "_ms"));
    for (const auto& m : metrics) field(csvField(m));
    out += ",dir,error\n";
    for (const SweepRow& r : s.rows) {
        out += std::to_string(r.index);
        for (const auto& [k, v] : r.settings) field(csvField(v));
        for (const auto& st : stages) field(csvNumber(r.timingsMs, st));
        for (const auto& m : metrics) field(csvNumber(r.metrics, m));
        field(csvField(r.dir));
        field(csvField(r.error));
        out += '\n';
    }
    return out;
}

std::string sweepSvg(const SweepReport& s) {
    ScatterChart chart;
    chart.title = fmt::format("{}: {} render time against {}", s.scene,
                              s.testRenderer == "realtime" ? "real-time" : "reference", s.metric);
    chart.xLabel = fmt::format("{} render time per frame (ms, median of {} frame{})",
                               s.testRenderer == "realtime" ? "real-time" : "reference", s.frames,
                               s.frames == 1 ? "" : "s");
    chartValue(s.metric, 0.0, &chart.yLabel);
    chart.lowerYIsBetter = lowerIsBetter(s.metric);
    for (const SweepRow& r : s.rows) {
        ChartPoint p;
        const auto t = r.timingsMs.find("total");
        const auto m = r.metrics.find(s.metric);
        p.x = t == r.timingsMs.end() ? NAN : t->second;
        p.y = m == r.metrics.end() ? NAN : chartValue(s.metric, m->second);
        p.label = r.label();
        chart.points.push_back(std::move(p));
    }
    return scatterSvg(chart);
}

namespace {

// A combination's row: its render, index (marked when on the front), settings, times and
// metrics; its error in a row under it.
std::string combinationRow(const SweepReport& s, const SweepRow& r, bool onFront,
                           const std::vector<std::string>& stages,
                           const std::vector<std::string>& metrics) {
    std::string h = "<tr>";
    h += r.error.empty()
             ? fmt::format("<td><img class=\"thumb\" src=\"{}\" alt=\"{}\"></td>",
                           urlPath(r.dir + "/" + s.testRenderer + ".png"), htmlEscape(r.label()))
             : "<td></td>";
    h += fmt::format("<td class=\"num\">{}{}</td>", r.index,
                     onFront ? " <span class=\"badge pass\" title=\"on the Pareto front: no other "
                               "combination is both faster and better\">Pareto</span>"
                             : "");
    for (const auto& [k, v] : r.settings) h += "<td class=\"mono\">" + htmlEscape(v) + "</td>";
    for (const auto& st : stages) {
        const auto it = r.timingsMs.find(st);
        h += "<td class=\"num\">" +
             (it == r.timingsMs.end() ? std::string("—") : fmt::format("{:.2f}", it->second)) +
             "</td>";
    }
    for (const auto& m : metrics) h += metricValueCell(r.metrics, m, m == s.metric);
    h += "</tr>\n";
    if (!r.error.empty())
        h += errorRow(1 + s.keys.size() + stages.size() + metrics.size(), r.error);
    return h;
}

}  // namespace

std::string sweepHtml(const SweepReport& s) {
    const auto stages = stageColumns(s);
    const auto metrics = metricColumns(s);
    // The front, to mark its rows in the table as in the chart.
    std::vector<ChartPoint> pts;
    for (const SweepRow& r : s.rows) {
        const auto t = r.timingsMs.find("total");
        const auto m = r.metrics.find(s.metric);
        pts.push_back({t == r.timingsMs.end() ? NAN : t->second,
                       m == r.metrics.end() ? NAN : chartValue(s.metric, m->second), ""});
    }
    const auto front = paretoFront(pts, lowerIsBetter(s.metric));
    const std::set<std::size_t> onFront(front.begin(), front.end());

    const std::string title = "twinrender sweep: " + s.scene;
    std::vector<std::string> facts = {
        fmt::format("{} of {} combinations", s.rows.size(), s.combinations),
        "test: " + htmlEscape(s.testRenderer), "reference: " + htmlEscape(s.referenceDescription),
        fmt::format("{} frame{} per combination (median)", s.frames, s.frames == 1 ? "" : "s")};
    if (!s.createdAt.empty()) facts.push_back(htmlEscape(s.createdAt));
    std::string h = pageHeader(title, std::nullopt, facts);
    h += "<section>\n<h2>Time against " + htmlEscape(s.metric) + "</h2>\n";
    h +=
        "<p class=\"lead\">Each point is one combination of the varied settings; the red line "
        "joins the "
        "Pareto front, the combinations that no other one beats in both time and " +
        htmlEscape(s.metric) +
        ". Data: <a href=\"sweep.csv\">sweep.csv</a>, <a href=\"sweep.json\">sweep.json</a>.</p>\n";
    h += "<img src=\"sweep.svg\" alt=\"time against " + htmlEscape(s.metric) +
         "\" style=\"max-width:100%;height:auto\">\n</section>\n";
    h += "<section>\n<h2>Combinations</h2>\n<div class=\"scroll\"><table "
         "class=\"scenes\">\n<thead><tr><th></th><th class=\"num\">#</th>";
    for (const auto& k : s.keys) h += "<th><span class=\"mono\">" + htmlEscape(k) + "</span></th>";
    for (const auto& st : stages)
        h += "<th class=\"num\">" + htmlEscape(st) + " <span class=\"unit\">ms</span></th>";
    for (const auto& m : metrics) h += metricHeaderCell(m);
    h += "</tr></thead>\n<tbody>\n";
    for (std::size_t i = 0; i < s.rows.size(); ++i)
        h += combinationRow(s, s.rows[i], onFront.count(i) > 0, stages, metrics);
    h += "</tbody></table></div>\n</section>\n</main>\n";
    return reportPage(title, h, s.createdAt, s.commandLine);
}

void writeSweepReport(const SweepReport& s, const fs::path& dir) {
    fs::create_directories(dir);
    core::writeTextFile(dir / "sweep.json", sweepJson(s).dump(2) + "\n");
    core::writeTextFile(dir / "sweep.csv", sweepCsv(s));
    core::writeTextFile(dir / "sweep.svg", sweepSvg(s));
    core::writeTextFile(dir / "index.html", sweepHtml(s));
}

}  // namespace twinrender::compare
