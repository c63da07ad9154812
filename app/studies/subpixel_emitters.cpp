// The subpixel_emitters study (docs/studies.md): a glowing ball from about 100 pixels across to
// a tenth of one, moved across a pixel at each size: the real-time image's emitted light against
// the reference's, its mean and how much it changes from frame to frame.
#include <fmt/format.h>

#include <algorithm>
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
constexpr double EMITTER_SCENE_FOV_Y_DEG = 40.0;  // the scene's

// The projected diameters the points aim at, pixels (quick: fewer, on a smaller image).
std::vector<double> emitterDiameters(bool quick) {
    return quick ? std::vector<double>{30.0, 3.0, 0.3}
                 : std::vector<double>{100.0, 30.0, 10.0, 3.0, 1.0, 0.5, 0.3, 0.1};
}

// The ball's positions at each size, as frames of a motion: moved by 1 / POSITIONS of a pixel
// right and up per frame, so that the frames cover a pixel and the next frame after the last
// repeats the first one pixel on (the image's pixels are alike).
int positions(bool quick) {
    return quick ? 2 : 4;
}

// The sub-pixel options: a series each.
struct Option {
    const char* series;
    const char* key;  // "": plain impostors
    double pixels;
};
const Option OPTIONS[] = {{"impostors", "", 0.0},
                          {"min_pixels 1", "realtime.particles.min_pixels", 1.0},
                          {"halo 2", "realtime.particles.halo_pixels", 2.0}};

// The reference's samples per pixel at a diameter: enough that the ball covers about 400 of
// the stratified sample cells (a square count, at least 16, at most raymarch.spp's 16384).
// Fewer, it counts the cells it covers more than it measures its area: a 0.3 px ball covers
// 18 of 256 cells, and the count varies by several with its position.
int referenceSpp(double diameter) {
    const double area = 0.25 * std::numbers::pi * diameter * diameter;
    const int side = static_cast<int>(std::ceil(std::sqrt(400.0 / area)));
    return std::clamp(side * side, 16, 16384);
}

}  // namespace

std::vector<StudyPoint> subpixelEmittersPoints(bool quick) {
    const double height = quick ? 48.0 : 96.0, width = quick ? 64.0 : 128.0;
    const double focal = focalPixels(height, EMITTER_SCENE_FOV_Y_DEG);
    // Up to 3 px the image is a window of 24 x 18 pixels about the ball, at the same focal
    // length: the reference's many samples per pixel are spent where the light is.
    constexpr double WINDOW_WIDTH = 24.0, WINDOW_HEIGHT = 18.0;
    std::vector<StudyPoint> pts;
    for (const Option& o : OPTIONS)
        for (const double diameter : emitterDiameters(quick))
            for (int k = 0; k < positions(quick); ++k) {
                const double distance = 2.0 * EMITTER_RADIUS * focal / diameter;
                const double shift = double(k) / positions(quick) * distance / focal;
                StudyPoint p{o.series,
                             NAN,
                             {set("camera.position", vec(shift, -distance, shift)),
                              set("camera.target", vec(shift, 0.0, shift)),
                              set("raymarch.spp", std::to_string(referenceSpp(diameter)))},
                             ""};
                if (*o.key) p.sets.push_back(set(o.key, fmt::format("{}", o.pixels)));
                const bool window = diameter <= 3.0;
                p.sets.push_back(set("camera.width", num(window ? WINDOW_WIDTH : width)));
                p.sets.push_back(set("camera.height", num(window ? WINDOW_HEIGHT : height)));
                if (window)
                    p.sets.push_back(
                        set("camera.fov_y_deg",
                            fmt::format("{:.17g}", 2.0 * std::atan(0.5 * WINDOW_HEIGHT / focal) *
                                                       180.0 / std::numbers::pi)));
                pts.push_back(std::move(p));
            }
    return pts;
}

// The ball's diameter on screen, pixels: its one particle's level set (volume W(r, h) at the
// raymarcher's surface level, solved for r by bisection) at its depth along the view axis (the
// same at every position of a size: the camera moves across it).
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
    const double depth = glm::dot(p - c.position, glm::normalize(c.target - c.position));
    return 2.0 * lo * focalPixels(c.height, c.fovYDeg) / depth;
}

void subpixelEmittersConclude(StudyResult& s) {
    const std::string metric = "flux.ratio";
    const auto within = [](double ratio) { return std::abs(ratio - 1.0) <= 0.10; };
    report::LineChart chart = seriesChart(s, metric);
    chart.series.clear();
    report::LineChart flickerChart = chart;
    chart.yLabel = "flux.ratio, mean over the positions (1: the reference's flux)";
    flickerChart.title = s.title + ": flicker";
    flickerChart.yLabel = "mean change of flux.ratio from frame to frame";
    report::StudyTable table{
        "flux",
        "Each series at each of the ball's sizes on screen, the ball moved across a pixel in "
        "equal steps (frames): the flux of the real-time image over the reference's "
        "(flux.ratio), its mean, least and greatest over the positions, and its flicker, the "
        "mean change of flux.ratio from one frame to the next (the last frame to the first "
        "included: the next step repeats it a pixel on).",
        {"series", "diameter (px)"},
        {"flux.ratio", "least", "greatest", "flicker"},
        {}};
    std::string finding;
    for (const auto& [name, rows] : bySeries(s)) {
        if (rows.empty()) continue;
        // The rows of one size: the positions, in frame order (bySeries keeps the order of
        // rows of equal x).
        struct Size {
            double x, mean, least, greatest, flicker;
            bool kept;  // every position within 10 % of the reference's flux
        };
        std::vector<Size> sizes;
        for (std::size_t i = 0; i < rows.size();) {
            std::size_t j = i;
            while (j < rows.size() && rows[j]->x == rows[i]->x) ++j;
            std::vector<double> r;
            for (std::size_t k = i; k < j; ++k) r.push_back(metricOf(*rows[k], metric));
            Size z{rows[i]->x, 0.0, INFINITY, -INFINITY, 0.0, true};
            for (std::size_t k = 0; k < r.size(); ++k) {
                z.mean += r[k] / double(r.size());
                z.least = std::min(z.least, r[k]);
                z.greatest = std::max(z.greatest, r[k]);
                z.kept = z.kept && within(r[k]);
                if (r.size() > 1)
                    z.flicker += std::abs(r[(k + 1) % r.size()] - r[k]) / double(r.size());
            }
            sizes.push_back(z);
            i = j;
        }
        report::LineSeries meanLine{name, {}, false}, flickerLine{name, {}, false};
        for (const Size& z : sizes) {
            const std::string px = fmt::format("{:.4g}", z.x);
            s.facts["flux_ratio"][name][px] = jsonOrNull(z.mean);
            s.facts["flux_ratio_least"][name][px] = jsonOrNull(z.least);
            s.facts["flux_ratio_greatest"][name][px] = jsonOrNull(z.greatest);
            s.facts["flicker"][name][px] = jsonOrNull(z.flicker);
            table.lines.push_back({{name, num(z.x)},
                                   {{"flux.ratio", z.mean},
                                    {"least", z.least},
                                    {"greatest", z.greatest},
                                    {"flicker", z.flicker}}});
            meanLine.points.push_back({z.x, z.mean, ""});
            flickerLine.points.push_back({z.x, z.flicker, ""});
        }
        chart.series.push_back(std::move(meanLine));
        flickerChart.series.push_back(std::move(flickerLine));
        // From the largest ball down: the smallest size down to which every position keeps the
        // flux within 10 % of the reference's. From the smallest up: the largest size up to
        // which every position does (the sizes a sub-pixel option is for).
        double downTo = NAN, upTo = NAN;
        for (auto it = sizes.rbegin(); it != sizes.rend() && it->kept; ++it) downTo = it->x;
        for (auto it = sizes.begin(); it != sizes.end() && it->kept; ++it) upTo = it->x;
        s.facts["within_10_percent_down_to_px"][name] = jsonOrNull(downTo);
        s.facts["within_10_percent_up_to_px"][name] = jsonOrNull(upTo);
        const Size& smallest = sizes.front();
        const auto worst = std::max_element(sizes.begin(), sizes.end(),
                                            [](auto& a, auto& b) { return a.flicker < b.flicker; });
        s.facts["most_flicker"][name] = {{"px", worst->x}, {"flicker", worst->flicker}};
        finding += fmt::format("{}{}: the flux within 10 % of the reference's at every position ",
                               finding.empty() ? "" : "; ", name);
        if (std::isfinite(upTo) && upTo == sizes.back().x)
            finding += "at every size";
        else if (std::isfinite(upTo))
            finding += fmt::format("at every size up to {} px across", num(upTo));
        else if (std::isfinite(downTo))
            finding += fmt::format("down to {} px across", num(downTo));
        else
            finding += "at no size";
        finding += fmt::format(", {} of it at {} px; flicker at most {} (at {} px)",
                               percent(smallest.mean), num(smallest.x), num(worst->flicker),
                               num(worst->x));
        if (std::isfinite(upTo) && upTo != sizes.back().x)
            chart.xMarks.push_back({upTo, name + " within 10 % below"});
    }
    s.chart = std::move(chart);
    s.figures.push_back({"flicker",
                         "The mean change of flux.ratio from one frame to the next as the ball "
                         "moves across a pixel, a line per series.",
                         std::move(flickerChart)});
    s.tables.push_back(std::move(table));
    s.finding = finding.empty() ? "no rows to compare" : finding;
}

}  // namespace twinrender::app::study
