#include "app/studies/common.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <string_view>

#include "compare/metric_table.h"
#include "compare/thresholds.h"

namespace twinrender::app::study {

double focalPixels(double height, double fovYDeg) {
    return 0.5 * height / std::tan(0.5 * fovYDeg * std::numbers::pi / 180.0);
}

std::vector<std::string> backedAway(std::string first, double distance, bool quick) {
    std::vector<std::string> sets = {std::move(first),
                                     set("camera.position", vec(0.0, -distance, 0.0))};
    if (quick) {
        sets.push_back(set("camera.width", "64"));
        sets.push_back(set("camera.height", "48"));
    }
    return sets;
}

std::vector<std::string> halfPixelAside(double distance, double height, double fovYDeg) {
    return cameraAt({.position = {0.0, -distance, 0.0}, .target = {}, .up = {0.0, 0.0, 1.0}}, true,
                    height, fovYDeg);
}

std::vector<std::string> cameraAt(const CameraPose& pose, bool aside, double height,
                                  double fovYDeg) {
    const auto& [p, t, up] = pose;
    const std::array<double, 3> forward = {t[0] - p[0], t[1] - p[1], t[2] - p[2]};
    const double distance = std::hypot(forward[0], forward[1], forward[2]);
    // The image's +x: forward x up, of unit length.
    std::array<double, 3> right = {forward[1] * up[2] - forward[2] * up[1],
                                   forward[2] * up[0] - forward[0] * up[2],
                                   forward[0] * up[1] - forward[1] * up[0]};
    const double norm = std::hypot(right[0], right[1], right[2]);
    const double shift = aside && norm > 0.0 ? 0.5 * distance / focalPixels(height, fovYDeg) : 0.0;
    for (double& r : right) r = norm > 0.0 ? r / norm * shift : 0.0;
    return {set("camera.position", vec(p[0] + right[0], p[1] + right[1], p[2] + right[2])),
            set("camera.target", vec(t[0] + right[0], t[1] + right[1], t[2] + right[2]))};
}

namespace {

bool isRepeat(const StudyRow& r) {
    const std::string_view suffix = REPEAT;
    return r.series.size() > suffix.size() && r.series.ends_with(suffix);
}

}  // namespace

double metricOf(const StudyRow& r, const std::string& metric) {
    const auto it = r.metrics.find(metric);
    return it == r.metrics.end() ? NAN : it->second;
}

SeriesRows bySeries(const StudyResult& s) {
    SeriesRows out;
    for (const StudyRow& r : s.rows) {
        if (isRepeat(r)) continue;
        auto it = std::find_if(out.begin(), out.end(),
                               [&](const auto& p) { return p.first == r.series; });
        if (it == out.end()) {
            out.push_back({r.series, {}});
            it = std::prev(out.end());
        }
        it->second.push_back(&r);
    }
    for (auto& [name, rows] : out)
        std::stable_sort(rows.begin(), rows.end(),
                         [](const StudyRow* a, const StudyRow* b) { return a->x < b->x; });
    return out;
}

const std::vector<const StudyRow*>* seriesRows(const SeriesRows& all, const std::string& name) {
    for (const auto& [n, rows] : all)
        if (n == name) return &rows;
    return nullptr;
}

double meanOf(const std::vector<const StudyRow*>& rows, const std::string& metric) {
    double sum = 0.0;
    int n = 0;
    for (const StudyRow* r : rows) {
        const double v = metricOf(*r, metric);
        if (std::isfinite(v)) {
            sum += v;
            ++n;
        }
    }
    return n ? sum / n : NAN;
}

double spreadAt(const StudyResult& s, const StudyRow& r, const std::string& metric) {
    const std::string series = r.series + REPEAT;
    const StudyRow* repeat = nullptr;
    for (const StudyRow& q : s.rows)
        if (q.series == series && (!repeat || std::abs(q.x - r.x) < std::abs(repeat->x - r.x)))
            repeat = &q;
    if (!repeat) return NAN;
    const double d = std::abs(metricOf(*repeat, metric) - metricOf(r, metric));
    return std::isfinite(d) ? d : NAN;
}

Order order(double a, double b, double noise) {
    if (!std::isfinite(a) || !std::isfinite(b) || !(std::abs(a - b) > (noise >= 0.0 ? noise : 0.0)))
        return Order::Tie;
    return a < b ? Order::Lower : Order::Higher;
}

std::vector<std::string> lowestOf(const std::vector<Measured>& candidates) {
    const Measured* best = nullptr;
    for (const Measured& c : candidates)
        if (std::isfinite(c.value) && (!best || c.value < best->value)) best = &c;
    std::vector<std::string> names;
    if (!best) return names;
    for (const Measured& c : candidates)
        if (std::isfinite(c.value) &&
            order(c.value, best->value, c.spread + best->spread) != Order::Higher)
            names.push_back(c.name);
    return names;
}

std::vector<std::string> highestOf(std::vector<Measured> candidates) {
    for (Measured& c : candidates) c.value = -c.value;
    return lowestOf(candidates);
}

double standardErrorOf(const std::vector<const StudyRow*>& rows, const std::string& metric) {
    const double mean = meanOf(rows, metric);
    double sum = 0.0;
    int n = 0;
    for (const StudyRow* r : rows) {
        const double v = metricOf(*r, metric);
        if (std::isfinite(v)) {
            sum += (v - mean) * (v - mean);
            ++n;
        }
    }
    return n >= 2 ? std::sqrt(sum / (n - 1) / n) : NAN;
}

std::string joinNames(const std::vector<std::string>& names) {
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i)
        out += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
    return out;
}

std::string xNumber(double x) {
    if (!std::isfinite(x)) return compare::formatValue(x);
    const double e = std::round(std::log10(std::abs(x)));
    if (std::abs(x) >= 1e4 && std::abs(x - std::pow(10.0, e)) < 1e-9 * std::abs(x))
        return fmt::format("1e{}", e);
    if (std::abs(x) >= 100 && std::abs(x) < 1e6 && x == std::round(x))
        return fmt::format("{:.0f}", x);
    return fmt::format("{:.3g}", x);
}

std::string num(double v) {
    if (v == 0.0) return "0";  // never "-0"
    return std::isfinite(v) ? fmt::format("{:.3g}", v) : std::string("unmeasured");
}

std::string percent(double fraction) {
    if (!std::isfinite(fraction)) return "unmeasured";
    if (std::abs(fraction) < 0.0005) return "0 %";  // never "-0.0 %"
    return std::abs(fraction) < 0.1 ? fmt::format("{:.1f} %", 100.0 * fraction)
                                    : fmt::format("{:.0f} %", 100.0 * fraction);
}

json jsonOrNull(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}

std::string set(const std::string& key, const std::string& value) {
    return key + "=" + value;
}
std::string vec(double x, double y, double z) {
    return fmt::format("[{:.9g}, {:.9g}, {:.9g}]", x, y, z);
}

std::map<double, double> gainOf(const StudyResult& s, const std::string& metric,
                                const std::string& on, const std::string& off) {
    const auto all = bySeries(s);
    const auto* a = seriesRows(all, on);
    const auto* b = seriesRows(all, off);
    std::map<double, double> gain;
    if (!a || !b) return gain;
    for (const StudyRow* r : *a)
        for (const StudyRow* q : *b)
            if (q->x == r->x || std::abs(q->x - r->x) < 1e-9 * std::abs(r->x))
                gain[r->x] = 1.0 - metricOf(*r, metric) / metricOf(*q, metric);
    return gain;
}

report::LineChart seriesChart(const StudyResult& s, const std::string& metric) {
    report::LineChart c;
    // The x axis carries its own label: the title names the study and the metric only, so that
    // it fits over the plot.
    c.title = fmt::format("{}: {}", s.title, metric);
    c.xLabel = s.xLabel;
    const std::string unit = compare::metricUnit(metric);
    c.yLabel = unit.empty() ? metric : fmt::format("{} ({})", metric, unit);
    c.xScale = s.xLog ? report::AxisScale::Log : report::AxisScale::Linear;
    for (const auto& [name, rows] : bySeries(s)) {
        report::LineSeries line{name, {}, false};
        for (const StudyRow* r : rows) line.points.push_back({r->x, metricOf(*r, metric), ""});
        c.series.push_back(std::move(line));
    }
    return c;
}

}  // namespace twinrender::app::study
