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
    // Each again with the camera turned half a pixel: the noise the conclusion's ties rest on.
    addRepeats(pts);
    return pts;
}

// Two things, each beyond the two rows' spreads (their difference from a render with the camera
// turned half a pixel): how each series' normal error at the largest angle stands to its
// face-on one, and at which angles SSSS lowers the error against none.
void viewAngleConclude(StudyResult& s) {
    const std::string metric = "normal.mean_deg";
    s.chart = seriesChart(s, metric);
    const SsssPairs pairs =
        ssssAgainstOff(s, bySeries(s), [](double x) { return fmt::format("{:g}", x); });
    if (pairs.on.empty()) {
        s.finding = "no pair of SSSS on/off renders to compare";
        return;
    }
    const auto &on = pairs.on, &off = pairs.off;
    std::vector<std::string> lower, tie, higher;
    for (std::size_t i = 0; i < on.size(); ++i) {
        const StudyRow& a = *on[i];
        const std::string x = fmt::format("{:g}", a.x);
        s.facts["normal_deg"][x] = jsonOrNull(metricOf(a, metric));
        s.facts["smoothness"][x] = jsonOrNull(metricOf(a, "smoothness.ratio"));
        const Order o = pairs.against[i];
        (o == Order::Lower ? lower : o == Order::Higher ? higher : tie).push_back(x + "°");
    }
    // The largest angle's error against face-on's.
    const Order onTrend = orderOf(s, *on.back(), *on.front(), metric);
    const Order offTrend = orderOf(s, *off.back(), *off.front(), metric);
    s.facts["toward_grazing"]["SSSS on"] = orderName(onTrend);
    s.facts["toward_grazing"]["SSSS off"] = orderName(offTrend);
    auto trend = [](Order o) {
        return o == Order::Lower    ? "lower toward grazing"
               : o == Order::Higher ? "higher toward grazing"
                                    : "a tie";
    };
    const StudyRow &first = *on.front(), &last = *on.back();
    std::string against;
    for (const auto& [names, what] :
         {std::pair{&lower, "lowers it at "}, std::pair{&tie, "ties with none at "},
          std::pair{&higher, "raises it at "}})
        if (!names->empty())
            against += (against.empty() ? "" : ", ") + std::string(what) + joinNames(*names);
    s.finding = fmt::format(
        "with SSSS the normal error is {}° face-on and {}° at {}°: {}; without, {}° and {}°: {} "
        "(beyond the noise: each row's difference from a render with the camera turned half a "
        "pixel); SSSS {}; smoothness.ratio from {} to {}",
        num(metricOf(first, metric)), num(metricOf(last, metric)), num(last.x), trend(onTrend),
        num(metricOf(*off.front(), metric)), num(metricOf(*off.back(), metric)), trend(offTrend),
        against, num(metricOf(first, "smoothness.ratio")), num(metricOf(last, "smoothness.ratio")));
}

}  // namespace twinrender::app::study
