// The temporal study (docs/studies.md): flicker along a camera orbit.
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "app/studies/common.h"
#include "app/studies/study_list.h"

namespace twinrender::app::study {

std::vector<StudyPoint> temporalPoints(bool quick) {
    const int frames = quick ? 4 : 12;
    const double step = 0.5 * std::numbers::pi / 180.0, radius = 3.5, height = 0.9;
    std::vector<StudyPoint> pts;
    for (const bool ssss : {true, false})
        for (int f = 0; f < frames; ++f) {
            const double a = -0.5 * std::numbers::pi + f * step;
            pts.push_back(
                {ssss ? "SSSS on" : "SSSS off",
                 double(f),
                 {set("realtime.ssss.enabled", ssss ? "true" : "false"),
                  set("camera.position", vec(radius * std::cos(a), radius * std::sin(a), height))},
                 ""});
        }
    return pts;
}

void temporalConclude(StudyResult& s) {
    const auto all = bySeries(s);
    s.chart = seriesChart(s, "temporal.frame_flip");
    for (auto& line : s.chart.series) line.name = "real-time, " + line.name;
    if (!all.empty()) {
        report::LineSeries ref{"reference", {}, true};
        for (const StudyRow* r : all.front().second)
            ref.points.push_back({r->x, metricOf(*r, "temporal.reference_frame_flip"), ""});
        s.chart.series.push_back(std::move(ref));
    }
    const double reference =
        all.empty() ? NAN : meanOf(all.front().second, "temporal.reference_frame_flip");
    s.facts["reference"] = jsonOrNull(reference);
    std::string parts, excess;
    for (const auto& [name, rows] : all) {
        const double v = meanOf(rows, "temporal.frame_flip");
        s.facts["realtime"][name] = jsonOrNull(v);
        s.facts["flicker"][name] = jsonOrNull(v - reference);
        parts += fmt::format("{}{} ({})", parts.empty() ? "" : ", ", num(v), name);
        excess += fmt::format("{}{:+.3g}", excess.empty() ? "" : ", ", v - reference);
    }
    s.finding = fmt::format(
        "flicker: real-time {} vs reference {} mean frame-to-frame ꟻLIP over {} frames (excess {})",
        parts, num(reference), all.empty() ? 0 : all.front().second.size(), excess);
}

}  // namespace twinrender::app::study
