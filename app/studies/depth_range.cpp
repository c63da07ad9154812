// The depth_range study (docs/studies.md): each depth mode from far/near 1e2 to 1e12.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "app/studies/common.h"
#include "app/studies/study_list.h"

namespace twinrender::app::study {

// The pair's layout as fractions of far (near stays 1): the planet at 0.5 far, radius 0.05 far;
// the moon at 0.45 far, radius 0.015 far, off-centre so it covers part of the planet's disc.
std::vector<StudyPoint> depthRangePoints(bool quick) {
    const std::vector<int> exponents = quick ? std::vector<int>{2, 5, 8, 12}
                                             : std::vector<int>{2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    std::vector<StudyPoint> pts;
    for (const char* mode : {"standard", "reversed", "log"})
        for (int e : exponents) {
            const double far = std::pow(10.0, e);
            pts.push_back({std::string(mode) + " depth",
                           far,
                           {set("realtime.depth", fmt::format("\"{}\"", mode)),
                            set("camera.far", fmt::format("{:.9g}", far)),
                            set("bodies.planet.center", vec(0, 0.5 * far, 0)),
                            set("bodies.planet.radius", fmt::format("{:.9g}", 0.05 * far)),
                            set("bodies.moon.center", vec(0.02 * far, 0.45 * far, 0.01 * far)),
                            set("bodies.moon.radius", fmt::format("{:.9g}", 0.015 * far))},
                           ""});
        }
    // Each again with the camera turned half a pixel: the noise the conclusion's ties rest on
    // (turned, not moved: the bodies lie a million times further than the camera's target).
    addRepeats(pts);
    return pts;
}

namespace {

const std::string OCCLUSION = "occlusion.error";

// The row with the study's lowest occlusion.error: what every row is held against.
const StudyRow* lowestRow(const SeriesRows& all) {
    const StudyRow* lowest = nullptr;
    for (const auto& [series, rows] : all)
        for (const StudyRow* r : rows)
            if (std::isfinite(metricOf(*r, OCCLUSION)) &&
                (!lowest || metricOf(*r, OCCLUSION) < metricOf(*lowest, OCCLUSION)))
                lowest = r;
    return lowest;
}

// A row is broken where its occlusion.error is above the lowest beyond the two rows' spreads
// (their difference from a render with the camera turned half a pixel), or not measured.
bool broken(const StudyResult& s, const StudyRow& r, const StudyRow& lowest) {
    return !std::isfinite(metricOf(r, OCCLUSION)) ||
           orderOf(s, r, lowest, OCCLUSION) == Order::Higher;
}

// How a broken row fails: nothing shows where both renders cover a pixel (id.mismatch not
// measured), the other body shows (id.mismatch above the lowest row's beyond the noise), or
// part of the bodies is lost.
std::string howBroken(const StudyResult& s, const StudyRow& r, const StudyRow& lowest) {
    if (!std::isfinite(metricOf(r, "id.mismatch"))) return "loses the bodies";
    return orderOf(s, r, lowest, "id.mismatch") == Order::Higher ? "orders the bodies wrongly"
                                                                 : "loses part of the bodies";
}

}  // namespace

// A series breaks at the smallest far/near from which every row is broken.
void depthRangeConclude(StudyResult& s) {
    s.chart = seriesChart(s, OCCLUSION);
    const SeriesRows all = bySeries(s);
    const StudyRow* lowest = lowestRow(all);
    if (!lowest) {
        s.finding = "no measured render to judge";
        return;
    }
    s.facts["lowest"] = metricOf(*lowest, OCCLUSION);
    s.facts["lowest_spread"] = jsonOrNull(spreadAt(s, *lowest, OCCLUSION));
    std::string finding;
    std::map<double, std::string> marks;
    for (const auto& [series, rows] : all) {
        const std::string mode = series.substr(0, series.find(' '));
        double breaks = NAN, worst = 0.0;
        const StudyRow* at = nullptr;
        for (std::size_t i = 0; i < rows.size(); ++i) {
            const StudyRow& r = *rows[i];
            if (std::isfinite(metricOf(r, OCCLUSION)))
                worst = std::max(worst, metricOf(r, OCCLUSION));
            s.facts["spread"][mode][xNumber(r.x)] = jsonOrNull(spreadAt(s, r, OCCLUSION));
            s.facts["broken"][mode][xNumber(r.x)] = broken(s, r, *lowest);
            bool fromHere = true;
            for (std::size_t j = i; j < rows.size(); ++j)
                fromHere = fromHere && broken(s, *rows[j], *lowest);
            if (fromHere && !at) {
                breaks = r.x;
                at = &r;
            }
        }
        s.facts["breaks_at"][mode] = jsonOrNull(breaks);
        s.facts["worst"][mode] = worst;
        finding += finding.empty() ? "" : "; ";
        if (at) {
            finding +=
                fmt::format("{} depth {} from far/near {} (occlusion.error {}, id.mismatch {})",
                            mode, howBroken(s, *at, *lowest), xNumber(breaks),
                            num(metricOf(*at, OCCLUSION)), num(metricOf(*at, "id.mismatch")));
            marks[breaks] += (marks[breaks].empty() ? "" : ", ") + mode;
        } else {
            finding += fmt::format("{} holds to {} (occlusion.error ≤ {})", mode,
                                   rows.empty() ? "-" : xNumber(rows.back()->x), num(worst));
        }
    }
    for (const auto& [x, modes] : marks) s.chart.xMarks.push_back({x, modes + " break"});
    s.finding = fmt::format(
        "{} (broken: occlusion.error above the lowest, {}, beyond the noise: each row's "
        "difference from a render with the camera turned half a pixel)",
        finding, num(metricOf(*lowest, OCCLUSION)));
}

}  // namespace twinrender::app::study
