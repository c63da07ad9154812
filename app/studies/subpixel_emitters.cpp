// The subpixel_emitters study (docs/studies.md): a glowing ball from about 100 pixels across to
// a tenth of one, the real-time image's emitted light against the reference's.
#include <fmt/format.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <string>
#include <vector>

#include "app/studies/common.h"
#include "app/studies/study_list.h"
#include "core/sph_kernel.h"

namespace twinrender::app::study {

namespace {

// The ball's radius in scene units, about: one particle of a unit ball, whose level set lies
// at 0.134 h (h = 1.3 (4 pi / 3)^(1/3)). The points aim at diameters with it; the rows' x is
// measured (subpixelEmitterPixels).
constexpr double EMITTER_RADIUS = 0.28;

// The projected diameters the points aim at, pixels (quick: fewer, on a smaller image).
std::vector<double> emitterDiameters(bool quick) {
    return quick ? std::vector<double>{30.0, 3.0, 0.3}
                 : std::vector<double>{100.0, 30.0, 10.0, 3.0, 1.0, 0.5, 0.3, 0.1};
}

}  // namespace

std::vector<StudyPoint> subpixelEmittersPoints(bool quick) {
    const double height = quick ? 48.0 : 96.0;  // the scene's fov_y is 40 degrees
    std::vector<StudyPoint> pts;
    for (const double minPixels : {0.0, 1.0})
        for (const double diameter : emitterDiameters(quick)) {
            const double distance = 2.0 * EMITTER_RADIUS * focalPixels(height, 40.0) / diameter;
            pts.push_back(
                {minPixels == 0.0 ? "impostors" : "min_pixels 1", NAN,
                 backedAway(set("realtime.particles.min_pixels", fmt::format("{}", minPixels)),
                            distance, quick),
                 ""});
        }
    return pts;
}

// The ball's diameter on screen, pixels: its one particle's level set (volume W(r, h) at the
// raymarcher's surface level, solved for r by bisection) seen from the camera's distance.
double subpixelEmitterPixels(const LoadedScene& s) {
    const auto& ps = s.particles.particles;
    if (ps.size() == 0) return NAN;
    const double h = ps.h[0], volume = ps.volume[0], level = s.raymarch.surfaceLevel;
    double lo = 0.0, hi = 2.0 * h;
    for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (volume * core::m4Kernel(mid, h) > level ? lo : hi) = mid;
    }
    const auto& c = s.scene.camera;
    const glm::dvec3 p(ps.position[0]);
    const double d = glm::length(c.position - p);
    return 2.0 * lo * focalPixels(c.height, c.fovYDeg) / d;
}

void subpixelEmittersConclude(StudyResult& s) {
    s.chart = seriesChart(s, "flux.ratio");
    const auto within = [](double ratio) { return std::abs(ratio - 1.0) <= 0.10; };
    std::string finding;
    // A line per series and size: the flux kept.
    report::StudyTable table{"flux",
                             "Each series at each of the ball's sizes on screen: the flux of the "
                             "real-time image over the reference's (flux.ratio).",
                             {"series", "diameter (px)"},
                             {"flux.ratio"},
                             {}};
    for (const auto& [name, rows] : bySeries(s)) {
        if (rows.empty()) continue;
        for (const StudyRow* r : rows) {
            s.facts["flux_ratio"][name][fmt::format("{:.4g}", r->x)] =
                jsonOrNull(metricOf(*r, "flux.ratio"));
            table.lines.push_back(
                {{name, num(r->x)}, {{"flux.ratio", metricOf(*r, "flux.ratio")}}});
        }
        // From the largest ball down: the smallest size down to which every row keeps the
        // flux within 10 % of the reference's. From the smallest up: the largest size up to
        // which every row does (the sizes a sub-pixel option is for).
        double downTo = NAN, upTo = NAN;
        for (auto it = rows.rbegin(); it != rows.rend() && within(metricOf(**it, "flux.ratio"));
             ++it)
            downTo = (*it)->x;
        for (auto it = rows.begin(); it != rows.end() && within(metricOf(**it, "flux.ratio")); ++it)
            upTo = (*it)->x;
        s.facts["within_10_percent_down_to_px"][name] = jsonOrNull(downTo);
        s.facts["within_10_percent_up_to_px"][name] = jsonOrNull(upTo);
        const double smallest = rows.front()->x;
        finding += fmt::format("{}{}: the flux within 10 % of the reference's ",
                               finding.empty() ? "" : "; ", name);
        if (std::isfinite(upTo) && upTo == rows.back()->x)
            finding += "at every size";
        else if (std::isfinite(upTo))
            finding += fmt::format("at every size up to {} px across", num(upTo));
        else if (std::isfinite(downTo))
            finding += fmt::format("down to {} px across", num(downTo));
        else
            finding += "at no size";
        finding += fmt::format(", {} of it at {} px",
                               percent(metricOf(*rows.front(), "flux.ratio")), num(smallest));
        if (std::isfinite(upTo)) s.chart.xMarks.push_back({upTo, name + " within 10 % below"});
    }
    s.tables.push_back(std::move(table));
    s.finding = finding.empty() ? "no rows to compare" : finding;
}

}  // namespace twinrender::app::study
