// The particle_size study (docs/studies.md): SSSS from about 40 pixels per particle to below one.
#include <fmt/format.h>

#include <cmath>
#include <functional>
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
    // Each again with the camera turned half a pixel: the noise the conclusion's ties rest on.
    addRepeats(pts);
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

SsssPairs ssssAgainstOff(StudyResult& s, const SeriesRows& all,
                         const std::function<std::string(double)>& key) {
    const std::string metric = "normal.mean_deg";
    const auto* on = seriesRows(all, "SSSS on");
    const auto* off = seriesRows(all, "SSSS off");
    if (!on || !off || on->empty() || on->size() != off->size()) return {};
    SsssPairs p{*on, *off, {}};
    for (std::size_t i = 0; i < on->size(); ++i) {
        const StudyRow &a = *(*on)[i], &b = *(*off)[i];
        const std::string x = key(a.x);
        p.against.push_back(orderOf(s, a, b, metric));
        s.facts["normal_gain"][x] = jsonOrNull(1.0 - metricOf(a, metric) / metricOf(b, metric));
        s.facts["against_off"][x] = orderName(p.against.back());
        s.facts["spread"]["SSSS on"][x] = jsonOrNull(spreadAt(s, a, metric));
        s.facts["spread"]["SSSS off"][x] = jsonOrNull(spreadAt(s, b, metric));
    }
    return p;
}

// SSSS helps at a size where its normal error is below SSSS off's beyond the two rows' spreads
// (their difference from a render with the camera turned half a pixel).
void particleSizeConclude(StudyResult& s) {
    const std::string metric = "normal.mean_deg";
    s.chart = seriesChart(s, metric);
    const SsssPairs pairs =
        ssssAgainstOff(s, bySeries(s), [](double x) { return fmt::format("{:.4g}", x); });
    if (pairs.on.empty()) {
        s.finding = "no pair of SSSS on/off renders to compare";
        return;
    }
    const auto &on = pairs.on, &off = pairs.off;
    const std::vector<Order>& against = pairs.against;
    // From the smallest particles up: the largest size up to which SSSS lowers the error at no
    // size.
    double stops = NAN;
    for (std::size_t i = 0; i < against.size() && against[i] != Order::Lower; ++i) stops = on[i]->x;
    const StudyRow &onBig = *on.back(), &offBig = *off.back();
    const double gainBig = 1.0 - metricOf(onBig, metric) / metricOf(offBig, metric);
    s.facts["stops_below_px"] = jsonOrNull(stops);
    s.facts["largest_px"] = onBig.x;
    s.finding = fmt::format(
        "at {} px per particle SSSS {} ({}° vs {}°; beyond the noise: each row's difference from "
        "a render with the camera turned half a pixel)",
        num(onBig.x),
        against.back() == Order::Lower    ? "lowers the normal error by " + percent(gainBig)
        : against.back() == Order::Higher ? "raises the normal error by " + percent(-gainBig)
                                          : "ties with none within the noise",
        num(metricOf(onBig, metric)), num(metricOf(offBig, metric)));
    if (std::isnan(stops)) {
        s.finding += fmt::format("; it still lowers it at {} px per particle", num(on.front()->x));
    } else if (stops == onBig.x) {
        s.finding += "; it lowers it at no size";
    } else {
        s.finding += fmt::format(
            "; at {} px per particle and below it no longer lowers it (the filter radius no "
            "longer spans the particle bumps)",
            num(stops));
        s.chart.xMarks.push_back({stops, "no gain below"});
    }
}

}  // namespace twinrender::app::study
