#include "report/sweep_report.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <string_view>
#include <tuple>

#include "compare/json_number.h"
#include "compare/metric_table.h"
#include "compare/thresholds.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/stage_table.h"
#include "core/write_roots.h"
#include "report/csv.h"
#include "report/html_page.h"
#include "report/markup.h"
#include "report/svg_chart.h"

namespace twinrender::report {

using compare::Better;
using compare::Check;
using compare::findMetric;
using compare::formatValue;
using compare::inMetricOrder;
using compare::MetricInfo;
using compare::metricLess;
using compare::metricUnit;
using compare::numberFromJson;
using compare::numbersJson;
using compare::overallStatus;
using compare::Status;
using compare::statusFromString;
using compare::toString;

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

void recordChecks(SweepRow& row, const std::vector<Check>& checks) {
    row.status = row.error.empty() ? overallStatus(checks) : Status::Fail;
    std::set<std::string> failed, warned;
    for (const Check& c : checks) {
        if (c.status == Status::Fail) failed.insert(c.metric);
        if (c.status == Status::Warn) warned.insert(c.metric);
    }
    for (const auto& m : failed) warned.erase(m);
    row.failed = inMetricOrder({failed.begin(), failed.end()});
    row.warned = inMetricOrder({warned.begin(), warned.end()});
}

Status sweepStatus(const SweepReport& s) {
    Status best = Status::Fail;
    for (const SweepRow& r : s.rows)
        if (r.status && *r.status < best) best = *r.status;
    return best;
}

const SweepRow* cheapestRow(const SweepReport& s, Status atWorst) {
    const SweepRow* cheapest = nullptr;
    double cheapestMs = INFINITY;
    for (const SweepRow& r : s.rows) {
        const auto t = r.timingsMs.find("total");
        if (!r.status || *r.status > atWorst || t == r.timingsMs.end() || !(t->second < cheapestMs))
            continue;
        cheapest = &r;
        cheapestMs = t->second;
    }
    return cheapest;
}

namespace {

// One word for a POSIX shell: as it is when it holds nothing the shell would read, else in
// single quotes (camera.position=[0,-4,1] would be a glob).
std::string shellWord(const std::string& text) {
    constexpr std::string_view SAFE = "-_.,=/:+@%";
    const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [&](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || SAFE.find(c) != SAFE.npos;
    });
    if (plain) return text;
    std::string quoted = "'";
    for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

// "3.20 ms: --set ...".
std::string timeAndArguments(const SweepRow& r) {
    return fmt::format("{:.2f} ms: {}", r.timingsMs.at("total"), setArguments(r));
}

}  // namespace

std::string setArguments(const SweepRow& r) {
    std::string args;
    for (const auto& [key, value] : r.settings)
        args += (args.empty() ? "--set " : " --set ") + shellWord(key + "=" + value);
    return args;
}

std::string whyNonePasses(const SweepReport& s) {
    if (s.rows.empty()) return "no combination was run";
    std::map<std::string, std::size_t> failed, warned;
    std::size_t errors = 0;
    for (const SweepRow& r : s.rows) {
        errors += !r.error.empty();
        for (const auto& m : r.failed) ++failed[m];
        for (const auto& m : r.warned) ++warned[m];
    }
    // Most frequent first; at equal counts failures before warnings, metrics in table order.
    std::vector<std::tuple<std::size_t, int, std::string>> causes;
    for (const auto& [m, n] : failed) causes.emplace_back(n, 0, m);
    for (const auto& [m, n] : warned) causes.emplace_back(n, 1, m);
    if (errors) causes.emplace_back(errors, 2, "");
    std::sort(causes.begin(), causes.end(), [](const auto& a, const auto& b) {
        if (std::get<0>(a) != std::get<0>(b)) return std::get<0>(a) > std::get<0>(b);
        if (std::get<1>(a) != std::get<1>(b)) return std::get<1>(a) < std::get<1>(b);
        return metricLess(std::get<2>(a), std::get<2>(b));
    });
    std::string text;
    for (const auto& [n, kind, metric] : causes) {
        const std::string what = kind == 2   ? std::string("rendering failed")
                                 : kind == 0 ? metric + " failed"
                                             : metric + " warned";
        text += text.empty() ? fmt::format("{} in {} of {} combinations", what, n, s.rows.size())
                             : fmt::format(", {} in {}", what, n);
    }
    return text.empty() ? "no combination was checked" : text;
}

std::vector<std::string> verdictLines(const SweepReport& s) {
    if (s.thresholdsFile.empty()) return {};
    if (const SweepRow* r = cheapestRow(s, Status::Pass))
        return {"cheapest passing: " + timeAndArguments(*r)};
    std::vector<std::string> lines = {"no combination passes: " + whyNonePasses(s)};
    if (const SweepRow* r = cheapestRow(s, Status::Warn))
        lines.push_back("cheapest with warnings only: " + timeAndArguments(*r));
    return lines;
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
    // The stages in the order a frame runs them (core/stage_table.h), the total first.
    return core::inStageOrder({all.begin(), all.end()});
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
        if (r.status) {
            j["status"] = toString(*r.status);
            j["failed"] = r.failed;
            j["warned"] = r.warned;
        }
        rows.push_back(std::move(j));
    }
    json j = {{"format", "twinrender-sweep"},
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
    if (!s.thresholdsFile.empty()) j["thresholds"] = s.thresholdsFile;
    if (s.sequence) j["sequence"] = true;
    return j;
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
        s.sequence = j.value("sequence", false);
        s.combinations = j.at("combinations").get<std::size_t>();
        s.createdAt = j.value("created", "");
        s.commandLine = j.value("command", "");
        s.thresholdsFile = j.value("thresholds", "");
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
            if (r.contains("status")) {
                row.status = statusFromString(r.at("status").get<std::string>());
                if (!row.status) throw bad(fmt::format("row {}: unknown status", row.index));
                row.failed = r.at("failed").get<std::vector<std::string>>();
                row.warned = r.at("warned").get<std::vector<std::string>>();
            }
            s.rows.push_back(std::move(row));
        }
        return s;
    } catch (const json::exception& e) {
        throw bad(e.what());
    }
}

namespace {

// Metric names in one CSV field: "beauty.flip normal.mean_deg".
std::string joined(const std::vector<std::string>& names) {
    return fmt::format("{}", fmt::join(names, " "));
}

}  // namespace

std::string sweepCsv(const SweepReport& s) {
    const auto stages = stageColumns(s);
    const auto metrics = metricColumns(s);
    std::string out = "index";
    // Appended piece by piece ("," + temporary trips GCC 12's -Wrestrict false positive).
    auto field = [&](const std::string& text) {
        out += ',';
        out += text;
    };
    const bool checked = !s.thresholdsFile.empty();
    for (const auto& k : s.keys) field(csvField(k));
    if (checked) out += ",status,failed,warned";
    for (const auto& st : stages) field(csvField("time." + st + "_ms"));
    for (const auto& m : metrics) field(csvField(m));
    out += ",dir,error\n";
    for (const SweepRow& r : s.rows) {
        out += std::to_string(r.index);
        for (const auto& [k, v] : r.settings) field(csvField(v));
        if (checked) {
            field(r.status ? std::string(toString(*r.status)) : "");
            field(csvField(joined(r.failed)));
            field(csvField(joined(r.warned)));
        }
        for (const auto& st : stages) field(csvNumber(r.timingsMs, st));
        for (const auto& m : metrics) field(csvNumber(r.metrics, m));
        field(csvField(r.dir));
        field(csvField(r.error));
        out += '\n';
    }
    return out;
}

std::string framesDescription(const SweepReport& s) {
    if (s.sequence)
        return fmt::format("median of the sequence's {} frame{}, each a new particle set", s.frames,
                           s.frames == 1 ? "" : "s");
    return fmt::format("median of {} frame{}", s.frames, s.frames == 1 ? "" : "s");
}

std::string sweepSvg(const SweepReport& s) {
    ScatterChart chart;
    chart.title = fmt::format("{}: {} render time against {}", s.scene,
                              s.testRenderer == "realtime" ? "real-time" : "reference", s.metric);
    chart.xLabel =
        fmt::format("{} render time per frame (ms, {})",
                    s.testRenderer == "realtime" ? "real-time" : "reference", framesDescription(s));
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

// The status a row's checks give a metric; nullopt when none failed or warned.
std::optional<Status> metricStatus(const SweepRow& r, const std::string& metric) {
    if (std::find(r.failed.begin(), r.failed.end(), metric) != r.failed.end()) return Status::Fail;
    if (std::find(r.warned.begin(), r.warned.end(), metric) != r.warned.end()) return Status::Warn;
    return std::nullopt;
}

// The row's verdict, the metrics past their bounds as its tooltip.
std::string verdictCell(const SweepRow& r) {
    if (!r.status) return "<td></td>";
    std::string title;
    if (!r.failed.empty()) title += "failed: " + joined(r.failed);
    if (!r.warned.empty()) title += (title.empty() ? "" : "; ") + ("warned: " + joined(r.warned));
    if (!r.error.empty()) title = "not rendered";
    return "<td" + (title.empty() ? "" : " title=\"" + htmlEscape(title) + "\"") + ">" +
           badge(*r.status) + "</td>";
}

// A combination's row: its render, index (marked when on the front, and when it is the
// cheapest that passes), its verdict against thresholds, settings, times and metrics (those
// past their bounds coloured); its error in a row under it.
std::string combinationRow(const SweepReport& s, const SweepRow& r, bool onFront, bool cheapest,
                           const std::vector<std::string>& stages,
                           const std::vector<std::string>& metrics) {
    const bool checked = !s.thresholdsFile.empty();
    std::string h = "<tr>";
    h += r.error.empty()
             ? fmt::format("<td><img class=\"thumb\" src=\"{}\" alt=\"{}\"></td>",
                           urlPath(r.dir + "/" + s.testRenderer + ".png"), htmlEscape(r.label()))
             : "<td></td>";
    h += fmt::format("<td class=\"num\">{}{}{}</td>", r.index,
                     onFront ? " <span class=\"badge pass\" title=\"on the Pareto front: no other "
                               "combination is both faster and better\">Pareto</span>"
                             : "",
                     cheapest ? " <span class=\"badge pass\" title=\"the fastest combination "
                                "that passes every bound\">cheapest</span>"
                              : "");
    if (checked) h += verdictCell(r);
    for (const auto& [k, v] : r.settings) h += "<td class=\"mono\">" + htmlEscape(v) + "</td>";
    for (const auto& st : stages) {
        const auto it = r.timingsMs.find(st);
        h += "<td class=\"num\">" +
             (it == r.timingsMs.end() ? std::string("—") : fmt::format("{:.2f}", it->second)) +
             "</td>";
    }
    for (const auto& m : metrics)
        h += metricValueCell(r.metrics, m, m == s.metric, metricStatus(r, m));
    h += "</tr>\n";
    if (!r.error.empty())
        h += errorRow((checked ? 2 : 1) + s.keys.size() + stages.size() + metrics.size(), r.error);
    return h;
}

// A combination named on the page, and the arguments that give its settings.
std::string combinationBlock(const SweepRow& r, const std::string& lead) {
    return fmt::format(
               "<p class=\"lead\">{} #{} (<span class=\"mono\">{}</span>), {:.2f} ms per "
               "frame. Its settings:</p>\n",
               lead, r.index, htmlEscape(r.label()), r.timingsMs.at("total")) +
           "<pre class=\"command\"><code>" + htmlEscape(setArguments(r)) + "</code></pre>\n";
}

// The answer of a sweep held to thresholds, above everything else: the cheapest combination
// that passes, or why none does.
std::string verdictSection(const SweepReport& s) {
    if (s.thresholdsFile.empty()) return "";
    const std::string file = "<span class=\"mono\">" + htmlEscape(s.thresholdsFile) + "</span>";
    const auto passing = std::count_if(s.rows.begin(), s.rows.end(),
                                       [](const SweepRow& r) { return r.status == Status::Pass; });
    std::string h = "<section>\n";
    if (const SweepRow* r = cheapestRow(s, Status::Pass)) {
        h += "<h2>Cheapest passing combination</h2>\n";
        h += combinationBlock(
            *r, fmt::format("{} of {} combinations pass every bound of {}; the fastest of them is",
                            passing, s.rows.size(), file));
    } else {
        h += "<h2>No combination passes</h2>\n";
        h += "<p class=\"lead\">No combination passes every bound of " + file + ": " +
             htmlEscape(whyNonePasses(s)) + ".</p>\n";
        if (const SweepRow* w = cheapestRow(s, Status::Warn))
            h += combinationBlock(*w, "The fastest with warnings only is");
    }
    return h + "</section>\n";
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

    const bool checked = !s.thresholdsFile.empty();
    const SweepRow* cheapest = cheapestRow(s, Status::Pass);

    const std::string title = "twinrender sweep: " + s.scene;
    std::vector<std::string> facts = {
        fmt::format("{} of {} combinations", s.rows.size(), s.combinations),
        "test: " + htmlEscape(s.testRenderer), "reference: " + htmlEscape(s.referenceDescription),
        "time: " + framesDescription(s)};
    if (s.sequence)
        facts.push_back("metrics: each at its worst frame, the flicker's mean and largest");
    if (checked) facts.push_back("thresholds: " + htmlEscape(s.thresholdsFile));
    if (!s.createdAt.empty()) facts.push_back(htmlEscape(s.createdAt));
    std::string h =
        pageHeader(title, checked ? std::optional(sweepStatus(s)) : std::nullopt, facts);
    h += verdictSection(s);
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
    if (checked) h += "<th>Verdict</th>";
    for (const auto& k : s.keys) h += "<th><span class=\"mono\">" + htmlEscape(k) + "</span></th>";
    for (const auto& st : stages)
        h += "<th class=\"num\">" + htmlEscape(st) + " <span class=\"unit\">ms</span></th>";
    for (const auto& m : metrics) h += metricHeaderCell(m);
    h += "</tr></thead>\n<tbody>\n";
    for (std::size_t i = 0; i < s.rows.size(); ++i)
        h += combinationRow(s, s.rows[i], onFront.count(i) > 0, &s.rows[i] == cheapest, stages,
                            metrics);
    h += "</tbody></table></div>\n</section>\n</main>\n";
    return reportPage(title, h, s.createdAt, s.commandLine);
}

void writeSweepReport(const SweepReport& s, const fs::path& dir) {
    core::makeFolders(dir);
    core::writeTextFile(dir / "sweep.json", sweepJson(s).dump(2) + "\n");
    core::writeTextFile(dir / "sweep.csv", sweepCsv(s));
    core::writeTextFile(dir / "sweep.svg", sweepSvg(s));
    core::writeTextFile(dir / "index.html", sweepHtml(s));
}

}  // namespace twinrender::report
