// The emissive_light and emissive_occluder studies (docs/studies.md, docs/light.md): the
// real-time estimates of the light a glowing ball casts on a slab against the reference's traced
// irradiance, as the ball moves around the camera from the middle of the view past the screen's
// edge to behind it, and as a disc moves between the ball and the slab. Screen-space gathering
// sees only the emitters on screen; the point light sees every emitter and no occluder.
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "app/studies/common.h"
#include "app/studies/study_list.h"
#include "report/svg_chart.h"

namespace twinrender::app::study {

namespace {

// A series: its name and its overrides.
struct EmissiveSeries {
    std::string name;
    std::vector<std::string> sets;
};

// The methods; ssem at the seed's diffuse setting (16 directions x 8 steps, the default) and on
// either side of it, for the cost against the error.
std::vector<EmissiveSeries> emissiveSeries(bool quick) {
    const std::string ssem = "realtime.emissive.method=\"ssem\"";
    std::vector<EmissiveSeries> out = {
        {"none", {"realtime.emissive.method=\"none\""}},
        {"point lights", {"realtime.emissive.method=\"point_lights\""}},
        {"ssem 16 x 8", {ssem}},
        // A sample behind the depth buffer by less than the thickness meets the surface there:
        // at the default (16 particle radii) the rays from under the lamp meet its front, and
        // also what they should pass behind; at 4 they pass behind the lamp's front.
        {"ssem 16 x 8, thickness 4", {ssem, "realtime.emissive.thickness=4"}},
        // The same rays in a target of the emitters alone with twice the view's tan(fov / 2):
        // a lamp just past the screen's edge still lights what is in view; nothing shadows.
        {"ssem target", {"realtime.emissive.method=\"ssem_target\""}},
    };
    if (!quick) {
        // A square target of the camera's height: what the aspect correction brings.
        out.push_back({"ssem target, square",
                       {"realtime.emissive.method=\"ssem_target\"",
                        "realtime.emissive.target_aspect=false"}});
        out.push_back(
            {"ssem 4 x 4", {ssem, "realtime.emissive.directions=4", "realtime.emissive.steps=4"}});
        out.push_back({"ssem 32 x 16",
                       {ssem, "realtime.emissive.directions=32", "realtime.emissive.steps=16"}});
        // The blur: none (the rays' noise as it is) and twice the default radius.
        out.push_back({"ssem 16 x 8, no blur", {ssem, "realtime.emissive.blur=\"none\""}});
        out.push_back({"ssem 16 x 8, blur 8", {ssem, "realtime.emissive.blur_radius=8"}});
    }
    return out;
}

// The lamp's angle from the view direction, seen from above the camera, degrees: 0 in the
// middle of the view, the screen's edge at about 26, 90 beside the camera, 180 behind it; quick:
// 30 too, just past the edge, inside "ssem target"'s wider view.
std::vector<double> lampAngles(bool quick) {
    if (quick) return {0.0, 30.0, 90.0};
    return {0.0, 10.0, 20.0, 30.0, 45.0, 60.0, 90.0, 135.0, 180.0};
}

// The lamp's centre at `deg`: on the circle about the camera's foot (0, -3) through the view's
// target, 0.6 above the slab.
std::string lampCentre(double deg) {
    const double a = deg * std::numbers::pi / 180.0;
    return set("bodies.lamp.center", vec(3.0 * std::sin(a), -3.0 + 3.0 * std::cos(a), 0.6));
}

// The time of the emissive pass in a row (the fastest of its frames); NaN without one.
double emissiveTime(const StudyRow& r) {
    const auto it = r.timingsMs.find("emissive");
    return it == r.timingsMs.end() ? NAN : it->second;
}

// Each series' line at each of `xs` (those it has) in `table`, their facts, and a finding's
// part per series: "<x><unit> <share of metric> <word>" for each x.
std::string tableAt(StudyResult& s, const std::vector<double>& xs, const std::string& xName,
                    const std::string& unit, const std::string& metric, const std::string& word,
                    report::StudyTable& table) {
    table.labels = {"series", xName};
    table.columns = {"indirect.rmse", "indirect.missed", "indirect.false", "beauty.hdrflip",
                     "emissive_ms"};
    std::string finding;
    for (const auto& [name, rows] : bySeries(s)) {
        std::string line;
        for (double x : xs)
            for (const StudyRow* r : rows) {
                if (r->x != x) continue;
                table.lines.push_back({{name, xNumber(x) + unit},
                                       {{"indirect.rmse", metricOf(*r, "indirect.rmse")},
                                        {"indirect.missed", metricOf(*r, "indirect.missed")},
                                        {"indirect.false", metricOf(*r, "indirect.false")},
                                        {"beauty.hdrflip", metricOf(*r, "beauty.hdrflip")},
                                        {"emissive_ms", emissiveTime(*r)}}});
                s.facts["series"][name][xNumber(x)] = {
                    {"rmse", jsonOrNull(metricOf(*r, "indirect.rmse"))},
                    {"missed", jsonOrNull(metricOf(*r, "indirect.missed"))},
                    {"false", jsonOrNull(metricOf(*r, "indirect.false"))}};
                line += fmt::format("{}{}{} {} {}", line.empty() ? "" : ", ", xNumber(x), unit,
                                    percent(metricOf(*r, metric)), word);
            }
        if (!line.empty())
            finding += fmt::format("{}{}: {}", finding.empty() ? "" : "; ", name, line);
    }
    return finding;
}

// The disc's distances from the lamp's axis, scene units: beside the lamp (no shadow of it in
// view) to right under it.
std::vector<double> discOffsets(bool quick) {
    if (quick) return {1.5, 0.0};
    return {1.5, 1.0, 0.7, 0.5, 0.3, 0.15, 0.0};
}

// Quick: a quarter of the pixels (the reference's rays dominate a study's time).
void quickCamera(StudyPoint& p) {
    p.sets.push_back("camera.width=64");
    p.sets.push_back("camera.height=48");
}

}  // namespace

std::vector<StudyPoint> emissiveLightPoints(bool quick) {
    std::vector<StudyPoint> pts;
    for (const EmissiveSeries& series : emissiveSeries(quick))
        for (double deg : lampAngles(quick)) {
            StudyPoint p{series.name, deg, series.sets, ""};
            p.sets.push_back(lampCentre(deg));
            if (quick) quickCamera(p);
            pts.push_back(std::move(p));
        }
    return pts;
}

void emissiveLightConclude(StudyResult& s) {
    s.chart = seriesChart(s, "indirect.rmse");
    for (auto& line : s.chart.series) line.dashed = line.name == "none";
    s.figures.push_back({"along_angle",
                         "indirect.rmse along the lamp's angle from the view direction, a line "
                         "per series; none dashed.",
                         s.chart});
    s.figures.push_back({"missed",
                         "indirect.missed (the share of the pixels the lamp lights in the "
                         "reference that the test leaves dark) along the lamp's angle from the "
                         "view direction, a line per series.",
                         seriesChart(s, "indirect.missed")});
    // The cost against the error over every point with the lamp on screen (within 20 degrees).
    report::ScatterChart scatter;
    scatter.title = "Light of emitting surfaces: the pass's time against its error";
    scatter.xLabel = "emissive pass (ms, one frame)";
    scatter.yLabel = "indirect.rmse, lamp on screen (lower is better)";
    for (const StudyRow& r : s.rows) {
        if (r.series == "none" || !r.error.empty() || r.x > 20.0) continue;
        scatter.points.push_back({emissiveTime(r), metricOf(r, "indirect.rmse"),
                                  fmt::format("{} at {}°", r.series, xNumber(r.x))});
        scatter.groups.push_back(r.series);
    }
    json front = json::array();
    for (std::size_t i : report::paretoFront(scatter.points, true))
        front.push_back({{"label", scatter.points[i].label},
                         {"emissive_ms", jsonOrNull(scatter.points[i].x)},
                         {"indirect_rmse", jsonOrNull(scatter.points[i].y)}});
    s.facts["pareto_front"] = front;
    s.scatter = scatter;
    // A line per series: on screen (0 degrees), just past the edge (30), beside (90), behind.
    report::StudyTable table{
        "by_angle",
        "Each series with the lamp in the middle of the view (0°), just past the screen's edge "
        "(30°), beside the camera (90°) and behind it (180°): the irradiance's RMS error, the "
        "share of the lit pixels missed and of the dark pixels lit, and the pass's time.",
        {},
        {},
        {}};
    const std::string finding =
        tableAt(s, {0.0, 30.0, 90.0, 180.0}, "lamp", "°", "indirect.missed", "missed", table);
    s.tables.push_back(std::move(table));
    s.finding =
        "share of the lamp's lit pixels left dark, by the lamp's angle from the view "
        "direction: " +
        finding;
}

std::vector<StudyPoint> emissiveOccluderPoints(bool quick) {
    std::vector<StudyPoint> pts;
    for (const EmissiveSeries& series : emissiveSeries(true))
        for (double x : discOffsets(quick)) {
            StudyPoint p{series.name, x, series.sets, ""};
            p.sets.push_back(set("bodies.shade.center", vec(x, 0.0, 0.45)));
            if (quick) quickCamera(p);
            pts.push_back(std::move(p));
        }
    return pts;
}

void emissiveOccluderConclude(StudyResult& s) {
    s.chart = seriesChart(s, "indirect.false");
    for (auto& line : s.chart.series) line.dashed = line.name == "none";
    s.figures.push_back({"rmse",
                         "indirect.rmse along the disc's distance from the lamp's axis, a line "
                         "per series; none dashed.",
                         seriesChart(s, "indirect.rmse")});
    report::StudyTable table{"by_offset",
                             "Each series with the disc beside the lamp (1.5) and right under it "
                             "(0): the irradiance's RMS error, the share of the lit pixels "
                             "missed and of the dark pixels lit (through the disc), and the "
                             "pass's time.",
                             {},
                             {},
                             {}};
    const std::string finding =
        tableAt(s, {1.5, 0.0}, "disc", "", "indirect.false", "lit through the disc", table);
    s.tables.push_back(std::move(table));
    s.finding =
        "share of the pixels dark in the reference that the test lights, by the disc's "
        "distance from the lamp's axis: " +
        finding;
}

}  // namespace twinrender::app::study
