#include "report/report_markdown.h"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <optional>
#include <vector>

#include "compare/baseline.h"
#include "compare/metric_table.h"
#include "core/image_io.h"
#include "report/markup.h"

namespace twinrender::report {

using compare::changeText;
using compare::Check;
using compare::formatValue;
using compare::inMetricOrder;
using compare::metricUnit;
using compare::Status;
using compare::toString;
using compare::worst;

namespace fs = std::filesystem;

namespace {

// A status as a table cell: a mark that reads at a glance, and the word.
std::string statusCell(Status s) {
    const char* mark = s == Status::Pass ? "✅" : s == Status::Warn ? "⚠️" : "❌";
    return fmt::format("{} {}", mark, toString(s));
}

// One metric of a scene that failed or warned: its checks of that status (a metric past its
// max is past its warn_max too; the warning says nothing more).
struct Flagged {
    std::string metric;
    Status status = Status::Pass;
    std::vector<const Check*> checks;
};

// The scene's metrics that failed or warned, in the metric table's order.
std::vector<Flagged> flaggedMetrics(const SceneReport& scene) {
    std::map<std::string, Flagged> byMetric;
    for (const Check& c : scene.checks) {
        if (c.status == Status::Pass) continue;
        Flagged& f = byMetric[c.metric];
        f.metric = c.metric;
        f.status = worst(f.status, c.status);
        f.checks.push_back(&c);
    }
    std::vector<std::string> keys;
    for (const auto& [metric, f] : byMetric) keys.push_back(metric);
    std::vector<Flagged> out;
    for (const std::string& m : inMetricOrder(keys)) {
        Flagged f = byMetric[m];
        std::erase_if(f.checks, [&](const Check* c) { return c->status != f.status; });
        out.push_back(std::move(f));
    }
    return out;
}

// The bound a check crossed, as the thresholds file names it: "max 0.15"; for the baseline,
// the blessed value and the worst value its tolerance allows.
std::string boundText(const Check& c) {
    if (c.bound == "baseline" && c.baseline)
        return fmt::format("baseline {}, worst allowed {}", formatValue(*c.baseline),
                           formatValue(c.limit));
    return fmt::format("{} {}", c.bound, formatValue(c.limit));
}

std::string valueText(const SceneReport& scene, const Flagged& f) {
    // Another test renderer's metric ("external:beauty.flip", report.h's SceneReport::tests) is
    // not among the scene's own: its check holds its value.
    const auto it = scene.metrics.find(f.metric);
    const bool checked = !f.checks.empty() && !std::isnan(f.checks.front()->value);
    if (it == scene.metrics.end() && !checked) return "not computed";
    const std::string unit = metricUnit(f.metric.substr(f.metric.find(':') + 1));
    return formatValue(it == scene.metrics.end() ? f.checks.front()->value : it->second) +
           (unit.empty() ? "" : " " + unit);
}

// The change from the blessed value; "—" when the scene's baseline does not have the metric.
std::string changeCell(const SceneReport& scene, const Flagged& f) {
    std::optional<double> base;
    if (const auto b = scene.baseline.find(f.metric); b != scene.baseline.end()) base = b->second;
    for (const Check* c : f.checks)
        if (c->baseline) base = *c->baseline;
    const auto v = scene.metrics.find(f.metric);
    if (!base || v == scene.metrics.end()) return "—";
    return changeText(v->second, *base);
}

std::string join(const std::vector<std::string>& cells, const std::string& separator) {
    std::string out;
    for (const std::string& c : cells) out += (out.empty() ? "" : separator) + c;
    return out;
}

std::string sceneRow(const SceneReport& scene, bool withChange) {
    const std::string page = urlPath(scene.name + "/index.html");
    std::vector<std::string> row = {fmt::format("[{}]({})", markdownEscape(scene.name), page),
                                    statusCell(scene.status())};
    if (!scene.error.empty()) {
        row.push_back("could not be rendered or compared: " + markdownEscape(scene.error));
        row.insert(row.end(), withChange ? 3 : 2, "");
        return "| " + join(row, " | ") + " |\n";
    }
    std::vector<std::string> metrics, values, bounds, changes;
    for (const Flagged& f : flaggedMetrics(scene)) {
        metrics.push_back(fmt::format("[{}]({}#metric-{}){}", markdownEscape(f.metric), page,
                                      urlPath(f.metric),
                                      f.status == Status::Warn ? " (warn)" : ""));
        values.push_back(markdownEscape(valueText(scene, f)));
        std::vector<std::string> crossed;
        for (const Check* c : f.checks) crossed.push_back(boundText(*c));
        bounds.push_back(markdownEscape(join(crossed, "; ")));
        changes.push_back(markdownEscape(changeCell(scene, f)));
    }
    row.push_back(join(metrics, "<br>"));
    row.push_back(join(values, "<br>"));
    row.push_back(join(bounds, "<br>"));
    if (withChange) row.push_back(join(changes, "<br>"));
    return "| " + join(row, " | ") + " |\n";
}

// "3 scenes: 1 fail, 1 warn, 1 pass."
std::string countsLine(const RunReport& run) {
    std::map<Status, int> n;
    for (const SceneReport& s : run.scenes) ++n[s.status()];
    std::vector<std::string> parts;
    for (Status s : {Status::Fail, Status::Warn, Status::Pass})
        if (n[s] > 0) parts.push_back(fmt::format("{} {}", n[s], toString(s)));
    return fmt::format("{} scene{}{}{}.", run.scenes.size(), run.scenes.size() == 1 ? "" : "s",
                       parts.empty() ? "" : ": ", join(parts, ", "));
}

}  // namespace

std::string summaryMarkdown(const RunReport& run) {
    std::string md = fmt::format("## twinrender: {}\n\n", statusCell(run.status()));
    md += countsLine(run);
    md += run.thresholdsFile.empty() ? " No thresholds file."
                                     : " Thresholds: " + markdownEscape(run.thresholdsFile) + ".";
    if (!run.baselineFile.empty()) md += " Baseline: " + markdownEscape(run.baselineFile) + ".";
    md += " [The report](index.html) has every metric, image and error map.\n\n";
    if (run.scenes.empty()) return md;
    const bool withChange = !run.baselineFile.empty();
    md += "| Scene | Status | Failed or warned | Value | Bound crossed |";
    md += withChange ? " Change from baseline |\n" : "\n";
    md += "| --- | --- | --- | ---: | --- |";
    md += withChange ? " ---: |\n" : "\n";
    for (const SceneReport& s : run.scenes) md += sceneRow(s, withChange);
    return md;
}

void writeSummaryMarkdown(const RunReport& run, const fs::path& file) {
    core::writeTextFile(file, summaryMarkdown(run));
}

}  // namespace twinrender::report
