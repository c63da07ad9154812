// The particle_size study (docs/studies.md): SSSS from about 40 pixels per particle to below one.
#include <fmt/format.h>

#include <cmath>
#include <iterator>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "app/studies/common.h"
#include "app/studies/study_list.h"

namespace twinrender::app::study {

// The camera moves along the line 25 degrees off the slab's normal through the target; the
// distances give about 40, 20, ... 0.6 pixels per particle (fewer, larger particles in quick).
std::vector<double> sizeDistances(bool quick) {
    return quick ? std::vector<double>{0.55, 2.2, 8.8, 35.0}
                 : std::vector<double>{0.37, 0.75, 1.5, 3.0, 6.0, 12.0, 25.0};
}
std::string sizeCamera(double distance) {
    const double a = 25.0 * std::numbers::pi / 180.0;
    return set("camera.position", vec(0.0, -distance * std::sin(a), 0.1 + distance * std::cos(a)));
}

std::vector<StudyPoint> particleSizePoints(bool quick) {
    std::vector<StudyPoint> pts;
    for (const bool ssss : {true, false})
        for (double d : sizeDistances(quick))
            pts.push_back({ssss ? "SSSS on" : "SSSS off",
                           NAN,
                           {set("realtime.ssss.enabled", ssss ? "true" : "false"), sizeCamera(d)},
                           ""});
    if (quick)
        for (auto& p : pts) p.sets.push_back(SIZE_QUICK_PARTICLES);
    return pts;
}

// Pixels per particle at the target: the impostor's diameter (2 radius_scale h, the body's mean
// h) over the distance, times the focal length in pixels.
double particlePixels(const LoadedScene& s) {
    const auto& c = s.scene.camera;
    const double d = std::sqrt((c.position.x - c.target.x) * (c.position.x - c.target.x) +
                               (c.position.y - c.target.y) * (c.position.y - c.target.y) +
                               (c.position.z - c.target.z) * (c.position.z - c.target.z));
    const double f = 0.5 * c.height / std::tan(0.5 * c.fovYDeg * std::numbers::pi / 180.0);
    const double h = s.particles.bodies.empty() ? 0.0 : s.particles.bodies.front().meanH;
    return 2.0 * s.realtime.particles.radiusScale * h * f / d;
}

void particleSizeConclude(StudyResult& s) {
    s.chart = seriesChart(s, "normal.mean_deg");
    const auto gain = gainOf(s, "normal.mean_deg", "SSSS on", "SSSS off");
    for (const auto& [x, g] : gain)
        s.facts["normal_gain"][fmt::format("{:.4g}", x)] = jsonOrNull(g);
    if (gain.empty()) {
        s.finding = "no pair of SSSS on/off renders to compare";
        return;
    }
    // From the largest particles down: where the gain falls below 10 % for good.
    double stops = NAN;
    for (auto it = gain.begin(); it != gain.end(); ++it) {
        bool below = true;
        for (auto jt = gain.begin(); jt != std::next(it); ++jt)
            below = below && !(jt->second >= 0.10);
        if (below) stops = it->first;
    }
    const auto& [xMax, gMax] = *gain.rbegin();
    const auto all = bySeries(s);
    const StudyRow* onBig = seriesRows(all, "SSSS on")->back();
    double offBig = NAN;
    for (const StudyRow* q : *seriesRows(all, "SSSS off"))
        if (q->x == onBig->x) offBig = metricOf(*q, "normal.mean_deg");
    s.facts["stops_below_px"] = jsonOrNull(stops);
    s.facts["largest_px"] = xMax;
    s.finding = fmt::format("SSSS {} the normal error by {} at {} px per particle ({}° vs {}°)",
                            gMax >= 0 ? "lowers" : "raises", percent(std::abs(gMax)), num(xMax),
                            num(metricOf(*onBig, "normal.mean_deg")), num(offBig));
    if (std::isfinite(stops)) {
        s.finding += fmt::format(
            "; at {} px per particle and below it helps less than 10 % (the filter radius no "
            "longer "
            "spans the particle bumps)",
            num(stops));
        s.chart.xMarks.push_back({stops, "gain < 10 %"});
    } else {
        s.finding += fmt::format("; it still helps by {} at {} px per particle",
                                 percent(gain.begin()->second), num(gain.begin()->first));
    }
}

}  // namespace twinrender::app::study
