// The emissive_light study (docs/studies.md, docs/light.md): the real-time estimates of the light
// a glowing ball casts on a slab against the reference's traced irradiance, as the ball moves
// around the camera from the middle of the view past the screen's edge to behind it. Screen-
// space gathering sees only the emitters on screen; the point light sees every emitter and no
// occluder.
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
    };
    if (!quick) {
        out.push_back(
            {"ssem 4 x 4", {ssem, "realtime.emissive.directions=4", "realtime.emissive.steps=4"}});
        out.push_back({"ssem 32 x 16",
                       {ssem, "realtime.emissive.directions=32", "realtime.emissive.steps=16"}});
    }
    return out;
}

// The lamp's angle from the view direction, seen from above the camera, degrees: 0 in the
// middle of the view, the screen's edge at about 26, 90 beside the camera, 180 behind it.
std::vector<double> lampAngles(bool quick) {
    if (quick) return {0.0, 90.0};
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

// The first row of `rows` (sorted by x) at or beyond x; nullptr when none.
const StudyRow* atOrBeyond(const std::vector<const StudyRow*>& rows, double x) {
    for (const StudyRow* r : rows)
        if (r->x >= x) return r;
    return nullptr;
}

}  // namespace

std::vector<StudyPoint> emissiveLightPoints(bool quick) {
    std::vector<StudyPoint> pts;
    for (const EmissiveSeries& series : emissiveSeries(quick))
        for (double deg : lampAngles(quick)) {
            StudyPoint p{series.name, deg, series.sets, ""};
            p.sets.push_back(lampCentre(deg));
            // Quick: a quarter of the pixels (the reference's rays dominate the study's time).
            if (quick) {
                p.sets.push_back("camera.width=64");
                p.sets.push_back("camera.height=48");
            }
            pts.push_back(std::move(p));
        }
    return pts;
}

void emissiveLightConclude(StudyResult& s) {
    s.chart = seriesChart(s, "indirect.rmse");
    for (auto& line : s.chart.series) line.dashed = line.name == "none";
    const auto all = bySeries(s);
    s.figures.push_back({"along_angle",
                         "indirect.rmse along the lamp's angle from the view direction, a line "
                         "per series; none dashed.",
                         s.chart});
    s.figures.push_back({"missed",
                         "indirect.missed (the share of the pixels the lamp lights in the "
                         "reference that the test leaves dark) along the lamp's angle from the "
                         "view direction, a line per series.",
                         seriesChart(s, "indirect.missed")});
    // The cost against the error over every point on screen (the lamp within 20 degrees).
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
        {"series", "lamp"},
        {"indirect.rmse", "indirect.missed", "indirect.false", "beauty.hdrflip", "emissive_ms"},
        {}};
    std::string finding;
    for (const auto& [name, rows] : all) {
        std::string line;
        for (double deg : {0.0, 30.0, 90.0, 180.0}) {
            const StudyRow* r = atOrBeyond(rows, deg);
            if (!r || (deg > 0.0 && r->x != deg)) continue;
            table.lines.push_back({{name, fmt::format("{}°", xNumber(r->x))},
                                   {{"indirect.rmse", metricOf(*r, "indirect.rmse")},
                                    {"indirect.missed", metricOf(*r, "indirect.missed")},
                                    {"indirect.false", metricOf(*r, "indirect.false")},
                                    {"beauty.hdrflip", metricOf(*r, "beauty.hdrflip")},
                                    {"emissive_ms", emissiveTime(*r)}}});
            s.facts["series"][name][xNumber(r->x)] = {
                {"rmse", jsonOrNull(metricOf(*r, "indirect.rmse"))},
                {"missed", jsonOrNull(metricOf(*r, "indirect.missed"))},
                {"false", jsonOrNull(metricOf(*r, "indirect.false"))}};
            line += fmt::format("{}{}° {} missed", line.empty() ? "" : ", ", xNumber(r->x),
                                percent(metricOf(*r, "indirect.missed")));
        }
        if (!line.empty())
            finding += fmt::format("{}{}: {}", finding.empty() ? "" : "; ", name, line);
    }
    s.tables.push_back(std::move(table));
    s.finding =
        "share of the lamp's lit pixels left dark, by the lamp's angle from the view "
        "direction: " +
        finding;
}

}  // namespace twinrender::app::study
