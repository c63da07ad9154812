// The view_angle study (docs/studies.md): SSSS from face-on to grazing.
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "app/studies/common.h"
#include "app/studies/study_list.h"

namespace twinrender::app::study {

std::vector<double> viewAngles(bool quick) {
    return quick ? std::vector<double>{0, 45, 80}
                 : std::vector<double>{0, 15, 30, 45, 60, 70, 80, 85};
}
// The camera at `deg` from the slab's normal, 3 from the target.
std::vector<std::string> angleCamera(double deg) {
    const double a = deg * std::numbers::pi / 180.0, d = 3.0;
    return {set("camera.position", vec(0.0, -d * std::sin(a), 0.1 + d * std::cos(a))),
            // Perpendicular to the view direction at every angle.
            set("camera.up", vec(0.0, std::cos(a), std::sin(a)))};
}

std::vector<StudyPoint> viewAnglePoints(bool quick) {
    std::vector<StudyPoint> pts;
    for (const bool ssss : {true, false})
        for (double deg : viewAngles(quick)) {
            StudyPoint p{ssss ? "SSSS on" : "SSSS off",
                         deg,
                         {set("realtime.ssss.enabled", ssss ? "true" : "false")},
                         ""};
            for (std::string& c : angleCamera(deg)) p.sets.push_back(std::move(c));
            pts.push_back(std::move(p));
        }
    return pts;
}

void viewAngleConclude(StudyResult& s) {
    s.chart = seriesChart(s, "normal.mean_deg");
    const auto all = bySeries(s);
    const auto* on = seriesRows(all, "SSSS on");
    const auto gain = gainOf(s, "normal.mean_deg", "SSSS on", "SSSS off");
    if (!on || on->empty() || gain.empty()) {
        s.finding = "no pair of SSSS on/off renders to compare";
        return;
    }
    const StudyRow& first = *on->front();
    const StudyRow& last = *on->back();
    for (const StudyRow* r : *on) {
        s.facts["normal_deg"][fmt::format("{:g}", r->x)] =
            jsonOrNull(metricOf(*r, "normal.mean_deg"));
        s.facts["smoothness"][fmt::format("{:g}", r->x)] =
            jsonOrNull(metricOf(*r, "smoothness.ratio"));
    }
    for (const auto& [x, g] : gain) s.facts["normal_gain"][fmt::format("{:g}", x)] = jsonOrNull(g);
    const double g0 = gain.begin()->second, g1 = gain.rbegin()->second;
    s.facts["growth"] = metricOf(last, "normal.mean_deg") / metricOf(first, "normal.mean_deg");
    s.finding = fmt::format(
        "with SSSS the normal error goes from {}° face-on to {}° at {}° ({}x); smoothing's gain "
        "over none goes from {} to {}, "
        "smoothness.ratio from {} to {}",
        num(metricOf(first, "normal.mean_deg")), num(metricOf(last, "normal.mean_deg")),
        num(last.x), num(s.facts["growth"].get<double>()), percent(g0), percent(g1),
        num(metricOf(first, "smoothness.ratio")), num(metricOf(last, "smoothness.ratio")));
}

}  // namespace twinrender::app::study
