// The subpixel_emitters study (docs/studies.md): a glowing ball from about 100 pixels across to
// a tenth of one, the real-time image's emitted light against the reference's.
#include <fmt/format.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
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

// Focal length in pixels of the scene's camera (fov_y 40 degrees) at `height` pixels.
double focalPixels(double height) {
    return 0.5 * height / std::tan(20.0 * std::numbers::pi / 180.0);
}

}  // namespace

std::vector<StudyPoint> subpixelEmittersPoints(bool quick) {
    const double height = quick ? 48.0 : 96.0;
    std::vector<StudyPoint> pts;
    for (const double minPixels : {0.0, 1.0})
        for (const double diameter : emitterDiameters(quick)) {
            const double distance = 2.0 * EMITTER_RADIUS * focalPixels(height) / diameter;
            StudyPoint p{minPixels == 0.0 ? "impostors" : "min_pixels 1",
                         NAN,
                         {set("realtime.particles.min_pixels", fmt::format("{}", minPixels)),
                          set("camera.position", vec(0.0, -distance, 0.0))},
                         ""};
            if (quick) {
                p.sets.push_back(set("camera.width", "64"));
                p.sets.push_back(set("camera.height", "48"));
            }
            pts.push_back(std::move(p));
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
    return 2.0 * lo * focalPixels(c.height) / d;
}

void subpixelEmittersConclude(StudyResult& s) {
    s.chart = seriesChart(s, "flux.ratio");
    const auto all = bySeries(s);
    std::string finding;
    for (const auto& [name, rows] : all) {
        // From the largest ball down: the smallest size down to which every row keeps the
        // flux within 10 % of the reference's.
        double keeps = NAN, smallest = NAN, last = NAN;
        for (auto it = rows.rbegin(); it != rows.rend(); ++it) {
            const double ratio = metricOf(**it, "flux.ratio");
            s.facts["flux_ratio"][name][fmt::format("{:.4g}", (*it)->x)] = jsonOrNull(ratio);
            if (!(std::abs(ratio - 1.0) <= 0.10)) break;
            keeps = (*it)->x;
        }
        if (!rows.empty()) {
            smallest = rows.front()->x;
            last = metricOf(*rows.front(), "flux.ratio");
        }
        s.facts["within_10_percent_down_to_px"][name] = jsonOrNull(keeps);
        finding +=
            fmt::format("{}{}: the flux within 10 % of the reference's {}, {} of it at {} px",
                        finding.empty() ? "" : "; ", name,
                        std::isfinite(keeps) ? fmt::format("down to {} px across", num(keeps))
                                             : std::string("at no size"),
                        percent(last), num(smallest));
        if (std::isfinite(keeps)) s.chart.xMarks.push_back({keeps, name + " within 10 %"});
    }
    s.finding = finding.empty() ? "no rows to compare" : finding;
}

}  // namespace twinrender::app::study
