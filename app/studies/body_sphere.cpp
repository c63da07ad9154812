// The body_sphere study (docs/studies.md): one ball backed away from about 100 pixels in
// radius on screen to one, drawn as its particles and as one whole-body sphere
// (realtime.particles.body_sphere_pixels), each against the reference.
#include "core/body_sphere.h"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <utility>
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

// The sphere's image matches the truth as well as the particles' where its coverage IoU is not
// lower and its ꟻLIP not higher beyond the noise: the two rows' spreads (their difference from
// a render half a pixel aside) added.
bool noWorse(const StudyResult& s, const StudyRow& sphere, const StudyRow& particles,
             const std::string& metric, bool higherIsBetter) {
    const double a = metricOf(sphere, metric), b = metricOf(particles, metric);
    if (std::isnan(a) && std::isnan(b)) return true;  // a ball too small to hold a pixel
    if (!std::isfinite(a) || !std::isfinite(b)) return false;
    const double noise = spreadAt(s, sphere, metric) + spreadAt(s, particles, metric);
    return order(a, b, noise) != (higherIsBetter ? Order::Lower : Order::Higher);
}

bool imageNoWorse(const StudyResult& s, const StudyRow& sphere, const StudyRow& particles) {
    return noWorse(s, sphere, particles, "coverage.iou", true) &&
           noWorse(s, sphere, particles, "beauty.flip", false);
}

// Its normals match as well: the mean normal error not higher beyond the noise.
bool normalsNoWorse(const StudyResult& s, const StudyRow& sphere, const StudyRow& particles) {
    return noWorse(s, sphere, particles, "normal.mean_deg", false);
}

// From the smallest ball up: the largest radius up to which `noWorse` holds at every size and
// `measured` is measured (NaN: not even at the smallest), and its index.
template <typename Test>
std::pair<double, std::size_t> noWorseUpTo(const StudyResult& s,
                                           const std::vector<const StudyRow*>& sphere,
                                           const std::vector<const StudyRow*>& particles,
                                           Test noWorse, const char* measured) {
    double upTo = NAN;
    std::size_t last = 0;
    for (std::size_t i = 0; i < sphere.size() && noWorse(s, *sphere[i], *particles[i]); ++i)
        if (std::isfinite(metricOf(*sphere[i], measured))) {
            upTo = sphere[i]->x;
            last = i;
        }
    return {upTo, last};
}

// The passes that draw the particles: the shadow map (the light's view holds every particle
// whatever the ball's size on screen), the G-buffer and the gradient normals.
double drawMs(const StudyRow& r) {
    return timeOf(r, "shadow") + timeOf(r, "gbuffer") + timeOf(r, "normals");
}

}  // namespace

std::vector<StudyPoint> bodySpherePoints(bool quick) {
    const double height = quick ? 48.0 : 240.0;  // the scene's fov_y is 40 degrees
    std::vector<StudyPoint> pts;
    for (const bool repeat : {false, true})
        for (const bool sphere : {false, true})
            for (const double radius : ballRadii(quick)) {
                const double distance = BALL_RADIUS * focalPixels(height, 40.0) / radius;
                StudyPoint p{
                    std::string(sphere ? "sphere" : "particles") + (repeat ? REPEAT : ""), NAN,
                    backedAway(set("realtime.particles.body_sphere_pixels", sphere ? "4096" : "0"),
                               distance, quick),
                    ""};
                if (repeat)
                    for (std::string& c : halfPixelAside(distance, height, 40.0))
                        p.sets.push_back(std::move(c));
                pts.push_back(std::move(p));
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
        "against the reference, ꟻLIP, and the real-time shadow, G-buffer and gradient normal "
        "passes' and frame's times (the fastest of 3 frames).",
        {"series", "radius (px)"},
        {"coverage.iou", "normal.mean_deg", "beauty.flip", "shadow_ms", "gbuffer_ms", "normals_ms",
         "total_ms"},
        {}};
    for (const auto& [name, rows] : all)
        for (const StudyRow* r : rows) {
            table.lines.push_back({{name, num(r->x)},
                                   {{"coverage.iou", metricOf(*r, "coverage.iou")},
                                    {"normal.mean_deg", metricOf(*r, "normal.mean_deg")},
                                    {"beauty.flip", metricOf(*r, "beauty.flip")},
                                    {"shadow_ms", timeOf(*r, "shadow")},
                                    {"gbuffer_ms", timeOf(*r, "gbuffer")},
                                    {"normals_ms", timeOf(*r, "normals")},
                                    {"total_ms", timeOf(*r, "total")}}});
            s.facts["draw_ms"][name][fmt::format("{:.4g}", r->x)] = jsonOrNull(drawMs(*r));
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
    for (const auto* rows : {particles, sphere})
        for (const StudyRow* r : *rows)
            for (const char* m : {"coverage.iou", "beauty.flip", "normal.mean_deg"})
                s.facts["spread"][m][r->series][fmt::format("{:.4g}", r->x)] =
                    jsonOrNull(spreadAt(s, *r, m));
    const auto [upTo, last] = noWorseUpTo(s, *sphere, *particles, imageNoWorse, "coverage.iou");
    const double normalsUpTo =
        noWorseUpTo(s, *sphere, *particles, normalsNoWorse, "normal.mean_deg").first;
    s.facts["no_worse_up_to_px"] = jsonOrNull(upTo);
    s.facts["normals_no_worse_up_to_px"] = jsonOrNull(normalsUpTo);
    const double sphereNormal = meanOf(*sphere, "normal.mean_deg");
    const double particleNormal = meanOf(*particles, "normal.mean_deg");
    const std::string normals = fmt::format(
        "its mean normal error {} degrees against the particles' {} (means over the sizes), "
        "{}",
        num(sphereNormal), num(particleNormal),
        std::isfinite(normalsUpTo) ? fmt::format("no higher up to {} px", num(normalsUpTo))
                                   : std::string("higher at every size measured"));
    if (!std::isfinite(upTo)) {
        s.finding = fmt::format(
            "the sphere's image is worse than the particles' already at {} px in radius "
            "(coverage IoU {} against {}, ꟻLIP {} against {}); {}",
            num((*sphere)[0]->x), num(metricOf(*(*sphere)[0], "coverage.iou")),
            num(metricOf(*(*particles)[0], "coverage.iou")),
            num(metricOf(*(*sphere)[0], "beauty.flip")),
            num(metricOf(*(*particles)[0], "beauty.flip")), normals);
        return;
    }
    const StudyRow& sp = *(*sphere)[last];
    const StudyRow& pa = *(*particles)[last];
    const double drawSaved = 1.0 - drawMs(sp) / drawMs(pa);
    const double totalSaved = 1.0 - timeOf(sp, "total") / timeOf(pa, "total");
    s.facts["draw_saved_at_threshold"] = jsonOrNull(drawSaved);
    s.facts["total_saved_at_threshold"] = jsonOrNull(totalSaved);
    s.chart.xMarks.push_back({upTo, "sphere no worse below"});
    s.finding = fmt::format(
        "one sphere's image matches the truth as well as the particles' (coverage IoU no "
        "lower, ꟻLIP no higher, beyond their spread half a pixel aside) up to {} px in radius on "
        "screen{}; there it saves {} of the "
        "passes that draw it (shadow map, G-buffer, normals: {} ms against {} ms) and {} of the "
        "frame's; {}",
        num(upTo), upTo == sphere->back()->x ? ", the largest size measured" : "",
        percent(drawSaved), num(drawMs(sp)), num(drawMs(pa)), percent(totalSaved), normals);
}

}  // namespace twinrender::app::study
