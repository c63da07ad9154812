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
    return pts;
}

// A series breaks at the smallest far/near from which occlusion.error (the reference's
// covered pixels showing another body or none) stays above the study's best value + 0.02.
void depthRangeConclude(StudyResult& s) {
    const std::string metric = "occlusion.error";
    double best = INFINITY;
    for (const StudyRow& r : s.rows)
        if (std::isfinite(metricOf(r, metric))) best = std::min(best, metricOf(r, metric));
    const double limit = (std::isfinite(best) ? best : 0.0) + 0.02;
    s.facts["limit"] = limit;
    std::string finding;
    s.chart = seriesChart(s, metric);
    std::map<double, std::string> marks;
    for (const auto& [series, rows] : bySeries(s)) {
        double breaks = NAN, worst = 0.0;
        const StudyRow* at = nullptr;
        for (std::size_t i = 0; i < rows.size(); ++i) {
            const double v = metricOf(*rows[i], metric);
            if (std::isfinite(v)) worst = std::max(worst, v);
            bool above = true;
            for (std::size_t j = i; j < rows.size(); ++j)
                above = above && !(metricOf(*rows[j], metric) <= limit);
            if (above && std::isnan(breaks)) {
                breaks = rows[i]->x;
                at = rows[i];
            }
        }
        const std::string mode = series.substr(0, series.find(' '));
        s.facts["breaks_at"][mode] = jsonOrNull(breaks);
        s.facts["worst"][mode] = worst;
        finding += finding.empty() ? "" : "; ";
        if (at) {
            // Wrong order (the other body shows) or lost (nothing shows).
            const double mismatch = metricOf(*at, "id.mismatch");
            finding += fmt::format(
                "{} depth {} from far/near {} (occlusion.error {}, id.mismatch {})", mode,
                std::isfinite(mismatch) && mismatch > 0.02 ? "orders the bodies wrongly"
                : metricOf(*at, metric) < 0.5              ? "loses part of the bodies"
                                                           : "loses the bodies",
                xNumber(breaks), num(metricOf(*at, metric)), num(mismatch));
            marks[breaks] += (marks[breaks].empty() ? "" : ", ") + mode;
        } else {
            finding += fmt::format("{} holds to {} (occlusion.error ≤ {})", mode,
                                   rows.empty() ? "-" : xNumber(rows.back()->x), num(worst));
        }
    }
    for (const auto& [x, modes] : marks) s.chart.xMarks.push_back({x, modes + " break"});
    s.finding = finding;
}

}  // namespace twinrender::app::study
