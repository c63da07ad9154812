// The body_sphere study (docs/studies.md): one ball backed away from about 100 pixels in
// radius on screen to one, drawn as its particles and as one whole-body sphere
// (realtime.particles.body_sphere_pixels), each against the reference.
#include "core/body_sphere.h"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "app/studies/common.h"
#include "app/studies/study_list.h"
#include "core/camera.h"
#include "realtime/body_sphere_lod.h"

namespace twinrender::app::study {

namespace {

// The ball's level-set radius in scene units, about (a unit ball of 3000 hcp particles; the
// rows' x is measured: bodySphereRadiusPixels).
constexpr double BALL_RADIUS = 1.1;

// The on-screen radii the points aim at, pixels (quick: fewer, on a smaller image).
std::vector<double> ballRadii(bool quick) {
    return quick ? std::vector<double>{20.0, 6.0, 2.0}
                 : std::vector<double>{100.0, 50.0, 30.0, 20.0, 10.0, 6.0, 4.0, 3.0, 2.0, 1.0};
}

double timeOf(const StudyRow& r, const char* stage) {
    const auto it = r.timingsMs.find(stage);
    return it == r.timingsMs.end() ? NAN : it->second;
}

// The sphere matches the truth as well as the particles where its coverage IoU is no lower and
// its mean normal error no higher, within the metrics' noise.
bool noWorse(const StudyRow& sphere, const StudyRow& particles) {
    return metricOf(sphere, "coverage.iou") >= metricOf(particles, "coverage.iou") - 1e-3 &&
           metricOf(sphere, "normal.mean_deg") <= metricOf(particles, "normal.mean_deg") + 0.1;
}

}  // namespace

std::vector<StudyPoint> bodySpherePoints(bool quick) {
    const double height = quick ? 48.0 : 240.0;  // the scene's fov_y is 40 degrees
    std::vector<StudyPoint> pts;
    for (const bool sphere : {false, true})
        for (const double radius : ballRadii(quick)) {
            const double distance = BALL_RADIUS * focalPixels(height, 40.0) / radius;
            pts.push_back(
                {sphere ? "sphere" : "particles", NAN,
                 backedAway(set("realtime.particles.body_sphere_pixels", sphere ? "4096" : "0"),
                            distance, quick),
                 ""});
        }
    return pts;
}

// The ball's level-set sphere's radius on screen, pixels (the whole-body sphere's own measure).
double bodySphereRadiusPixels(const LoadedScene& s) {
    const std::vector<core::BodySphere> spheres =
        core::bodySpheres(s.particles, s.realtime.particles.surfaceLevel);
    if (spheres.empty()) return NAN;
    return realtime::projectedRadiusPixels(core::Camera(s.scene.camera), spheres[0].centre,
                                           spheres[0].radius);
}

void bodySphereConclude(StudyResult& s) {
    s.chart = seriesChart(s, "coverage.iou");
    const SeriesRows all = bySeries(s);
    report::StudyTable table{
        "sizes",
        "Each series at each of the ball's radii on screen: coverage IoU and mean normal error "
        "against the reference, ꟻLIP, and the real-time G-buffer pass's and frame's times.",
        {"series", "radius (px)"},
        {"coverage.iou", "normal.mean_deg", "beauty.flip", "gbuffer_ms", "total_ms"},
        {}};
    for (const auto& [name, rows] : all)
        for (const StudyRow* r : rows) {
            table.lines.push_back({{name, num(r->x)},
                                   {{"coverage.iou", metricOf(*r, "coverage.iou")},
                                    {"normal.mean_deg", metricOf(*r, "normal.mean_deg")},
                                    {"beauty.flip", metricOf(*r, "beauty.flip")},
                                    {"gbuffer_ms", timeOf(*r, "gbuffer")},
                                    {"total_ms", timeOf(*r, "total")}}});
            s.facts["gbuffer_ms"][name][fmt::format("{:.4g}", r->x)] =
                jsonOrNull(timeOf(*r, "gbuffer"));
            s.facts["total_ms"][name][fmt::format("{:.4g}", r->x)] =
                jsonOrNull(timeOf(*r, "total"));
        }
    s.tables.push_back(std::move(table));
    const auto* particles = seriesRows(all, "particles");
    const auto* sphere = seriesRows(all, "sphere");
    if (!particles || !sphere || particles->size() != sphere->size() || particles->empty()) {
        s.finding = "no pairs of rows to compare";
        return;
    }
    // From the smallest ball up: the largest radius up to which the sphere is no worse at every
    // size, and the times there.
    double upTo = NAN;
    std::size_t last = 0;
    for (std::size_t i = 0; i < sphere->size() && noWorse(*(*sphere)[i], *(*particles)[i]); ++i) {
        upTo = (*sphere)[i]->x;
        last = i;
    }
    s.facts["no_worse_up_to_px"] = jsonOrNull(upTo);
    if (!std::isfinite(upTo)) {
        s.finding = fmt::format(
            "the sphere is worse than the particles already at {} px in radius (coverage IoU "
            "{} against {})",
            num((*sphere)[0]->x), num(metricOf(*(*sphere)[0], "coverage.iou")),
            num(metricOf(*(*particles)[0], "coverage.iou")));
        return;
    }
    const StudyRow& sp = *(*sphere)[last];
    const StudyRow& pa = *(*particles)[last];
    const double gbufferSaved = 1.0 - timeOf(sp, "gbuffer") / timeOf(pa, "gbuffer");
    const double totalSaved = 1.0 - timeOf(sp, "total") / timeOf(pa, "total");
    s.facts["gbuffer_saved_at_threshold"] = jsonOrNull(gbufferSaved);
    s.facts["total_saved_at_threshold"] = jsonOrNull(totalSaved);
    s.chart.xMarks.push_back({upTo, "sphere no worse below"});
    s.finding = fmt::format(
        "one sphere matches the truth as well as the particles (coverage IoU no lower, mean "
        "normal error no higher) up to {} px in radius on screen{}; there it saves {} of the "
        "G-buffer pass's time ({} ms against {} ms) and {} of the frame's",
        num(upTo), upTo == sphere->back()->x ? ", the largest size measured" : "",
        percent(gbufferSaved), num(timeOf(sp, "gbuffer")), num(timeOf(pa, "gbuffer")),
        percent(totalSaved));
}

}  // namespace twinrender::app::study
