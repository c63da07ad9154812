#include "app/studies.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>

#include "compare/metric_table.h"
#include "compare/thresholds.h"
#include "core/install_layout.h"
#include "core/stage_table.h"
#include "report/study_summary.h"

namespace twinrender::app {

namespace {

using nlohmann::json;
using report::StudyResult;
using report::StudyRow;

double metricOf(const StudyRow& r, const std::string& metric) {
    const auto it = r.metrics.find(metric);
    return it == r.metrics.end() ? NAN : it->second;
}

// The rows of each series, in order of first appearance, each sorted by x.
std::vector<std::pair<std::string, std::vector<const StudyRow*>>> bySeries(const StudyResult& s) {
    std::vector<std::pair<std::string, std::vector<const StudyRow*>>> out;
    for (const StudyRow& r : s.rows) {
        auto it = std::find_if(out.begin(), out.end(),
                               [&](const auto& p) { return p.first == r.series; });
        if (it == out.end()) {
            out.push_back({r.series, {}});
            it = std::prev(out.end());
        }
        it->second.push_back(&r);
    }
    for (auto& [name, rows] : out)
        std::stable_sort(rows.begin(), rows.end(),
                         [](const StudyRow* a, const StudyRow* b) { return a->x < b->x; });
    return out;
}

const std::vector<const StudyRow*>* seriesRows(
    const std::vector<std::pair<std::string, std::vector<const StudyRow*>>>& all,
    const std::string& name) {
    for (const auto& [n, rows] : all)
        if (n == name) return &rows;
    return nullptr;
}

// The mean of the finite values of a metric over rows; NaN when there are none.
double meanOf(const std::vector<const StudyRow*>& rows, const std::string& metric) {
    double sum = 0.0;
    int n = 0;
    for (const StudyRow* r : rows) {
        const double v = metricOf(*r, metric);
        if (std::isfinite(v)) {
            sum += v;
            ++n;
        }
    }
    return n ? sum / n : NAN;
}

// A far/near or resolution as people write it: 1e6, 2048, 0.6.
std::string xNumber(double x) {
    if (!std::isfinite(x)) return compare::formatValue(x);
    const double e = std::round(std::log10(std::abs(x)));
    if (std::abs(x) >= 1e4 && std::abs(x - std::pow(10.0, e)) < 1e-9 * std::abs(x))
        return fmt::format("1e{}", e);
    if (std::abs(x) >= 100 && std::abs(x) < 1e6 && x == std::round(x))
        return fmt::format("{:.0f}", x);
    return fmt::format("{:.3g}", x);
}

std::string num(double v) {
    return std::isfinite(v) ? fmt::format("{:.3g}", v) : compare::formatValue(v);
}

std::string percent(double fraction) {
    return std::abs(fraction) < 0.1 ? fmt::format("{:.1f} %", 100.0 * fraction)
                                    : fmt::format("{:.0f} %", 100.0 * fraction);
}

json jsonOrNull(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}

std::string set(const std::string& key, const std::string& value) {
    return key + "=" + value;
}
std::string vec(double x, double y, double z) {
    return fmt::format("[{:.9g}, {:.9g}, {:.9g}]", x, y, z);
}

// ---- depth_range ------------------------------------------------------------------------------

// The pair's layout as fractions of far (near stays 1): the planet at 0.5 far, radius 0.05 far;
// the moon at 0.45 far, radius 0.015 far, off-centre so it covers part of the planet's disc.
std::vector<StudyPoint> depthPoints(bool quick) {
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
void depthConclude(StudyResult& s) {
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

// ---- particle_size ----------------------------------------------------------------------------

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
const char* const SIZE_QUICK_PARTICLES = "bodies.slab.particles=6000";

std::vector<StudyPoint> sizePoints(bool quick) {
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

// The gain of SSSS: 1 - error with it / error without it, per x.
std::map<double, double> gainOf(const StudyResult& s, const std::string& metric,
                                const std::string& on, const std::string& off) {
    const auto all = bySeries(s);
    const auto* a = seriesRows(all, on);
    const auto* b = seriesRows(all, off);
    std::map<double, double> gain;
    if (!a || !b) return gain;
    for (const StudyRow* r : *a)
        for (const StudyRow* q : *b)
            if (q->x == r->x || std::abs(q->x - r->x) < 1e-9 * std::abs(r->x))
                gain[r->x] = 1.0 - metricOf(*r, metric) / metricOf(*q, metric);
    return gain;
}

void sizeConclude(StudyResult& s) {
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

// ---- view_angle -------------------------------------------------------------------------------

std::vector<double> viewAngles(bool quick) {
    return quick ? std::vector<double>{0, 45, 80}
                 : std::vector<double>{0, 15, 30, 45, 60, 70, 80, 85};
}
// The camera at `deg` from the slab's normal, 3 from the target.
std::vector<std::string> angleCamera(double deg) {
    const double a = deg * std::numbers::pi / 180.0, d = 3.0;
    return {set("camera.position", vec(0.0, -d * std::sin(a), 0.1 + d * std::cos(a))),
            // Perpendicular to the view direction at every angle.
            set("camera.up", vec(0.0, std::cos(a), std::sin(a)))};
}

std::vector<StudyPoint> anglePoints(bool quick) {
    std::vector<StudyPoint> pts;
    for (const bool ssss : {true, false})
        for (double deg : viewAngles(quick)) {
            StudyPoint p{ssss ? "SSSS on" : "SSSS off",
                         deg,
                         {set("realtime.ssss.enabled", ssss ? "true" : "false")},
                         ""};
            for (std::string& c : angleCamera(deg)) p.sets.push_back(std::move(c));
            pts.push_back(std::move(p));
        }
    return pts;
}

void angleConclude(StudyResult& s) {
    s.chart = seriesChart(s, "normal.mean_deg");
    const auto all = bySeries(s);
    const auto* on = seriesRows(all, "SSSS on");
    const auto gain = gainOf(s, "normal.mean_deg", "SSSS on", "SSSS off");
    if (!on || on->empty() || gain.empty()) {
        s.finding = "no pair of SSSS on/off renders to compare";
        return;
    }
    const StudyRow& first = *on->front();
    const StudyRow& last = *on->back();
    for (const StudyRow* r : *on) {
        s.facts["normal_deg"][fmt::format("{:g}", r->x)] =
            jsonOrNull(metricOf(*r, "normal.mean_deg"));
        s.facts["smoothness"][fmt::format("{:g}", r->x)] =
            jsonOrNull(metricOf(*r, "smoothness.ratio"));
    }
    for (const auto& [x, g] : gain) s.facts["normal_gain"][fmt::format("{:g}", x)] = jsonOrNull(g);
    const double g0 = gain.begin()->second, g1 = gain.rbegin()->second;
    s.facts["growth"] = metricOf(last, "normal.mean_deg") / metricOf(first, "normal.mean_deg");
    s.finding = fmt::format(
        "with SSSS the normal error goes from {}° face-on to {}° at {}° ({}x); smoothing's gain "
        "over none goes from {} to {}, "
        "smoothness.ratio from {} to {}",
        num(metricOf(first, "normal.mean_deg")), num(metricOf(last, "normal.mean_deg")),
        num(last.x), num(s.facts["growth"].get<double>()), percent(g0), percent(g1),
        num(metricOf(first, "smoothness.ratio")), num(metricOf(last, "smoothness.ratio")));
}

// ---- thin_casters -----------------------------------------------------------------------------

std::vector<StudyPoint> shadowPoints(bool quick) {
    const std::vector<int> res =
        quick ? std::vector<int>{64, 256, 1024} : std::vector<int>{64, 128, 256, 512, 1024, 2048};
    const std::vector<double> biases =
        quick ? std::vector<double>{0.1, 2.0} : std::vector<double>{0.1, 0.5, 2.0};
    std::vector<StudyPoint> pts;
    for (double b : biases)
        for (int r : res)
            pts.push_back({fmt::format("map, bias {:g}", b),
                           double(r),
                           {"realtime.shadows=\"map\"",
                            set("realtime.shadow_map.resolution", std::to_string(r)),
                            set("realtime.shadow_map.bias", fmt::format("{:g}", b))},
                           ""});
    // The baseline does not use the map: one render, drawn across the axis.
    pts.push_back({"occlusion spheres", double(res.front()), {"realtime.shadows=\"spheres\""}, ""});
    pts.push_back({"occlusion spheres", double(res.back()), {"realtime.shadows=\"spheres\""}, ""});
    // The ring's shadow covers a few hundred pixels at the scene's 96 x 54; the full study
    // doubles that so one pixel moves IoU by less.
    if (!quick)
        for (auto& p : pts) {
            p.sets.push_back("camera.width=192");
            p.sets.push_back("camera.height=108");
        }
    return pts;
}

void shadowConclude(StudyResult& s) {
    s.chart = seriesChart(s, "shadow.iou");
    for (auto& line : s.chart.series) line.dashed = line.name == "occlusion spheres";
    const auto all = bySeries(s);
    // The best map series at the finest resolution, and how coarse it can go within 0.02 of it.
    std::string bestSeries;
    double bestIou = -INFINITY;
    for (const auto& [name, rows] : all)
        if (name.rfind("map", 0) == 0 && !rows.empty() &&
            metricOf(*rows.back(), "shadow.iou") > bestIou) {
            bestIou = metricOf(*rows.back(), "shadow.iou");
            bestSeries = name;
        }
    if (bestSeries.empty()) {
        s.finding = "no shadow-map render to judge";
        return;
    }
    const auto& best = *seriesRows(all, bestSeries);
    double enough = best.back()->x;
    for (auto it = best.rbegin(); it != best.rend(); ++it) {
        if (!(metricOf(**it, "shadow.iou") >= bestIou - 0.02)) break;
        enough = (*it)->x;
    }
    const auto& smallest = *seriesRows(all, all.front().first);  // the smallest bias
    const auto& largest = *seriesRows(all, [&] {
        std::string last;
        for (const auto& [name, rows] : all)
            if (name.rfind("map", 0) == 0) last = name;
        return last;
    }());
    const auto* spheres = seriesRows(all, "occlusion spheres");
    const double sphereIou = spheres ? meanOf(*spheres, "shadow.iou") : NAN;
    s.facts["best_series"] = bestSeries;
    s.facts["best_iou"] = bestIou;
    s.facts["enough_resolution"] = enough;
    s.facts["acne"] = jsonOrNull(metricOf(*smallest.back(), "shadow.false_shadow"));
    s.facts["leaks"] = jsonOrNull(metricOf(*largest.back(), "shadow.missed_shadow"));
    s.facts["spheres_iou"] = jsonOrNull(sphereIou);
    s.chart.xMarks.push_back({enough, "within 0.02 of best"});
    s.finding = fmt::format(
        "{} reaches shadow.iou {} (within 0.02 of its {} at {}) from {} texels; {}: acne {} of the "
        "pixels facing the light; {}: leaks {}; "
        "occlusion spheres: IoU {}",
        bestSeries,
        num(metricOf(
            *[&] {
                for (const StudyRow* r : best)
                    if (r->x == enough) return r;
                return best.back();
            }(),
            "shadow.iou")),
        num(bestIou), xNumber(best.back()->x), xNumber(enough), all.front().first,
        percent(metricOf(*smallest.back(), "shadow.false_shadow")),
        largest.empty() ? "" : largest.back()->series,
        percent(metricOf(*largest.back(), "shadow.missed_shadow")), num(sphereIou));
}

// ---- collision --------------------------------------------------------------------------------

std::vector<StudyPoint> collisionPoints(bool quick) {
    // Gap between the two surfaces (radius 0.6 each), scene units; < 0 overlapping.
    const std::vector<double> gaps =
        quick ? std::vector<double>{0.2, 0.0, -0.15}
              : std::vector<double>{0.3, 0.15, 0.05, 0.0, -0.1, -0.2, -0.3};
    std::vector<StudyPoint> pts;
    for (const bool ssss : {true, false})
        for (double g : gaps) {
            const double c = 0.6 + 0.5 * g;
            pts.push_back(
                {ssss ? "SSSS on" : "SSSS off",
                 g,
                 {set("realtime.ssss.enabled", ssss ? "true" : "false"),
                  set("bodies.cold.center", vec(-c, 0, 0)), set("bodies.hot.center", vec(c, 0, 0))},
                 ""});
        }
    return pts;
}

void collisionConclude(StudyResult& s) {
    s.chart = seriesChart(s, "contact.uv_mean");
    const auto all = bySeries(s);
    const auto* on = seriesRows(all, "SSSS on");
    const auto* off = seriesRows(all, "SSSS off");
    if (!on || !off) {
        s.finding = "no pair of SSSS on/off renders to compare";
        return;
    }
    // In contact: touching or overlapping (gap <= 0).
    auto touching = [](const std::vector<const StudyRow*>& rows) {
        std::vector<const StudyRow*> t;
        for (const StudyRow* r : rows)
            if (r->x <= 0.0) t.push_back(r);
        return t.empty() ? rows : t;
    };
    const double uvOn = meanOf(touching(*on), "contact.uv_mean"),
                 uvOff = meanOf(touching(*off), "contact.uv_mean");
    const double eOn = meanOf(touching(*on), "contact.emission_rmse"),
                 eOff = meanOf(touching(*off), "contact.emission_rmse");
    const double interior = meanOf(touching(*on), "uv.mean");
    s.facts["contact_uv"] = {{"ssss_on", jsonOrNull(uvOn)}, {"ssss_off", jsonOrNull(uvOff)}};
    s.facts["contact_emission"] = {{"ssss_on", jsonOrNull(eOn)}, {"ssss_off", jsonOrNull(eOff)}};
    s.facts["interior_uv"] = jsonOrNull(interior);
    auto change = [](double a, double b) {
        return std::isfinite(a) && std::isfinite(b) && b > 0
                   ? fmt::format("{:+.0f} %", 100.0 * (a / b - 1.0))
                   : std::string("n/a");
    };
    // Emission is constant per body here: a band error below this is rounding, not bleeding.
    constexpr double EMISSION_FLOOR = 1e-4;
    const std::string emission =
        std::max(eOn, eOff) < EMISSION_FLOOR
            ? fmt::format("emission does not bleed (band error below {:g} either way)",
                          EMISSION_FLOOR)
            : fmt::format("emission error {} with SSSS, {} without ({} from smoothing)", num(eOn),
                          num(eOff), change(eOn, eOff));
    s.facts["contact_over_interior"] = jsonOrNull(uvOn / interior);
    s.finding = fmt::format(
        "in contact, the uv error along the bodies' boundary is {} with SSSS and {} without ({} "
        "from smoothing), {}x the "
        "interior's {}; {}",
        num(uvOn), num(uvOff), change(uvOn, uvOff), num(uvOn / interior), num(interior), emission);
}

// ---- temporal ---------------------------------------------------------------------------------

std::vector<StudyPoint> orbitPoints(bool quick) {
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

// ---- flicker ----------------------------------------------------------------------------------

// The surface methods of the flicker study.
const char* const FLICKER_METHODS[] = {"none", "ssss", "bilateral", "narrow_range",
                                       "curvature_flow"};

// A group of the flicker study's series: a particle model on the churning ball, or a real
// simulation sequence with the default particles (field radii, exact gradient normals). Each
// method of a group is a series of its own, "<method> (<group>)": the study compares each frame
// with the previous one of its series.
struct FlickerGroup {
    std::string name;    // "OpenSPH collision": the series' suffix, the facts' key
    std::string legend;  // its lines' suffix in the legend of its chart, drawn dashed; "": none
    std::string scene;   // relative to scenes/studies/
    std::string figure;  // the file of its chart; "": its series are in the study's chart
    int first;           // the sequence's first frame: a point's x is its frame minus this
    int frames, quickFrames;
    std::vector<std::string> sets;  // what the group's points add; quick runs add quickSets
    std::vector<std::string> quickSets;
};

const std::string CHURN = "churn";

const std::vector<FlickerGroup>& flickerGroups() {
    // Quick runs (the tests) render the real sequences at 80x60, the churning ball's size, with a
    // shadow map of 512 texels a side (still 6 texels a pixel): the 2048 of the default costs
    // most of such a frame on llvmpipe.
    const std::vector<std::string> quarter = {set("camera.width", "80"), set("camera.height", "60"),
                                              set("realtime.shadow_map.resolution", "512")};
    static const std::vector<FlickerGroup> groups = {
        {CHURN, "", "flicker.toml", "", 0, 6, 3, {}, {}},
        // Impostor spheres (fixed radii, each sphere's own normal): the surface a screen-space
        // filter was made to smooth.
        {CHURN + ", impostor spheres",
         "impostors",
         "flicker.toml",
         "",
         0,
         6,
         3,
         {set("realtime.particles.radius", "\"fixed\""),
          set("realtime.particles.normal", "\"sphere\"")},
         {}},
        {"OpenSPH collision", "", "../collision_sequence.toml", "collision", 10, 5, 3, {}, quarter},
        {"LAMMPS splash", "", "../splash_sequence.toml", "splash", 16, 5, 3, {}, quarter},
    };
    return groups;
}

std::string flickerSeries(const std::string& method, const FlickerGroup& g) {
    return fmt::format("{} ({})", method, g.name);
}

std::vector<StudyPoint> flickerPoints(bool quick) {
    std::vector<StudyPoint> pts;
    for (const FlickerGroup& g : flickerGroups())
        for (const char* method : FLICKER_METHODS)
            for (int f = 0; f < (quick ? g.quickFrames : g.frames); ++f) {
                StudyPoint p{flickerSeries(method, g),
                             double(f),
                             {set("realtime.surface.method", fmt::format("\"{}\"", method)),
                              set("sequence.first", std::to_string(g.first + f)),
                              set("sequence.last", std::to_string(g.first + f))},
                             g.scene};
                p.sets.insert(p.sets.end(), g.sets.begin(), g.sets.end());
                if (quick) p.sets.insert(p.sets.end(), g.quickSets.begin(), g.quickSets.end());
                pts.push_back(std::move(p));
            }
    return pts;
}

// Per group: the method with the least and the most mean flicker, with their normal flicker; a
// table of every method's means; the churning ball's series in the study's chart, each real
// sequence's in a figure of its own.
void flickerConclude(StudyResult& s) {
    const auto all = bySeries(s);
    const std::string metric = "temporal.flicker", normal = "temporal.normal_flicker_deg";
    report::LineChart empty = seriesChart(s, metric);
    empty.series.clear();
    s.chart = empty;
    s.chart.title = s.title + ", churning ball: " + metric;
    s.chart.width = 960;  // room in the legend for "curvature_flow (impostors)"
    report::StudyTable table{"summary",
                             "Per group and method, the mean over the frames after the first of "
                             "temporal.flicker and temporal.normal_flicker_deg.",
                             {"group", "method"},
                             {metric, normal},
                             {}};
    std::string parts, agree;
    for (const FlickerGroup& g : flickerGroups()) {
        report::LineChart chart = empty;
        chart.title = fmt::format("{}, {}: {}", s.title, g.name, metric);
        std::string least, most;
        double lo = INFINITY, hi = -INFINITY, loNormal = NAN, hiNormal = NAN;
        for (const char* method : FLICKER_METHODS) {
            const std::string name = flickerSeries(method, g);
            const auto* rows = seriesRows(all, name);
            if (!rows) continue;
            const double v = meanOf(*rows, metric), n = meanOf(*rows, normal);
            s.facts["flicker"][name] = jsonOrNull(v);
            s.facts["normal_flicker_deg"][name] = jsonOrNull(n);
            table.lines.push_back({{g.name, method}, {{metric, v}, {normal, n}}});
            if (std::isfinite(v) && v < lo) lo = v, loNormal = n, least = method;
            if (std::isfinite(v) && v > hi) hi = v, hiNormal = n, most = method;
            report::LineSeries line{
                g.legend.empty() ? method : fmt::format("{} ({})", method, g.legend),
                {},
                !g.legend.empty()};
            for (const StudyRow* r : *rows) line.points.push_back({r->x, metricOf(*r, metric), ""});
            chart.series.push_back(std::move(line));
        }
        s.facts["groups"][g.name] = {{"least", least},
                                     {"least_flicker", jsonOrNull(lo)},
                                     {"least_normal_flicker_deg", jsonOrNull(loNormal)},
                                     {"most", most},
                                     {"most_flicker", jsonOrNull(hi)},
                                     {"most_normal_flicker_deg", jsonOrNull(hiNormal)}};
        parts +=
            fmt::format("{}{}: least {} ({:+.2g}, {:+.2g}°), most {} ({:+.2g}, {:+.2g}°)",
                        parts.empty() ? "" : "; ", g.name, least, lo, loNormal, most, hi, hiNormal);
        if (g.figure.empty()) {
            std::move(chart.series.begin(), chart.series.end(), std::back_inserter(s.chart.series));
            continue;
        }
        s.figures.push_back(
            {g.figure,
             fmt::format("{} of each surface method over the frames of {} "
                         "(scenes/{}), the default particles.",
                         metric, g.name, std::filesystem::path(g.scene).filename().string()),
             std::move(chart)});
        // Does the real sequence's least agree with the churning ball's?
        const std::string churn = s.facts["groups"][CHURN].value("least", "");
        agree += fmt::format("{}{} {}", agree.empty() ? "" : ", ", g.name,
                             least == churn ? "agrees" : "differs (" + least + ")");
    }
    s.tables.push_back(std::move(table));
    s.finding = fmt::format(
        "flicker against the truth (mean real-time minus reference frame-to-frame ꟻLIP, and of "
        "the normal; below 0 a method changes less than the truth does): {}; against the "
        "churning ball's least, {}",
        parts, agree);
}

// ---- methods ----------------------------------------------------------------------------------

// A surface method (realtime.surface.method) and its main parameter: the one that sets the
// filter's reach, in particle radii (steps for curvature flow). The default is the renderer's
// (realtime/settings.h); the full study also takes the values `step` below and above it.
struct MethodSweep {
    std::string name;               // the series' method: "bilateral"
    std::vector<std::string> sets;  // what selects it
    const char* key;                // the main parameter's key; nullptr: none has none
    double defaultValue;
    double step;  // the full study's values: default / step, default, default * step
    // What it is measured against along particle size and view angle: the same surface
    // unfiltered ("none" for SSSS and the depth normals, the depth normals for a depth filter);
    // "" for none itself.
    std::string control;
};

// The unfiltered surface with the normals a depth filter would rebuild from it: the example
// pass-through shader with realtime.surface.shader_normals, the control of the depth filters.
const std::string DEPTH_NORMALS = "depth_normals";

std::vector<MethodSweep> methodSweeps() {
    using realtime::SurfaceMethod;
    const realtime::Settings d;
    auto method = [](SurfaceMethod m) {
        return set("realtime.surface.method", fmt::format("\"{}\"", realtime::toString(m)));
    };
    const std::string none(realtime::toString(SurfaceMethod::None));
    return {
        {none, {method(SurfaceMethod::None)}, nullptr, 0.0, 1.0, ""},
        {DEPTH_NORMALS,
         {method(SurfaceMethod::Shader),
          set("realtime.surface.shader",
              fmt::format(
                  "\"{}\"",
                  (core::resourceDir() / "examples" / "surface_pass_through.glsl").string())),
          "realtime.surface.shader_normals=true"},
         nullptr,
         0.0,
         1.0,
         none},
        {"ssss",
         {method(SurfaceMethod::Ssss)},
         "realtime.ssss.radius_scale",
         d.ssss.radiusScale,
         2.0,
         none},
        {"bilateral",
         {method(SurfaceMethod::Bilateral)},
         "realtime.surface.bilateral.radius",
         d.surface.bilateral.radius,
         2.0,
         DEPTH_NORMALS},
        {"narrow_range",
         {method(SurfaceMethod::NarrowRange)},
         "realtime.surface.narrow_range.radius",
         d.surface.narrowRange.radius,
         2.0,
         DEPTH_NORMALS},
        // Curvature flow reaches about sqrt(2 n time_step) pixels after n steps.
        {"curvature_flow",
         {method(SurfaceMethod::CurvatureFlow)},
         "realtime.surface.curvature_flow.iterations",
         double(d.surface.curvatureFlow.iterations),
         4.0,
         DEPTH_NORMALS},
    };
}

// The values a sweep takes: the default and, in the full study, one step below it; quick and
// full, one step above.
std::vector<double> sweepValues(const MethodSweep& m, bool quick) {
    if (!m.key) return {0.0};
    if (quick) return {m.defaultValue, m.defaultValue * m.step};
    return {m.defaultValue / m.step, m.defaultValue, m.defaultValue * m.step};
}

// The particle shapes every method is rendered with. "sphere" is the renderer's default and is
// not set, any other shape is (realtime.particles.shape); each shape is a series of its own.
const std::vector<std::string> SHAPES = {"sphere", "ellipsoid"};

// The study scenes whose own x the methods are also rendered along, at their defaults.
const std::string SIZE_SCENE = "particle_size";
const std::string ANGLE_SCENE = "view_angle";

struct SuiteScene {
    std::string name;               // scenes/<name>.toml
    std::vector<std::string> sets;  // what the study changes in it
};

// The default suite (scenes/*.toml) at the size `run` renders it, opensph_ball (800 x 600
// there) at 320 x 240; of the two sequences the OpenSPH impact at one frame (splash_sequence's
// frames lie beside splash_sheet's); quick: the planet and the splash sheet, small.
std::vector<SuiteScene> suiteScenes(bool quick) {
    if (quick)
        return {
            {"planet", {"camera.width=160", "camera.height=120", "bodies.planet.particles=3000"}},
            {"splash_sheet", {"camera.width=160", "camera.height=120"}}};
    return {{"contact", {}},
            {"heated", {}},
            {"opensph_ball", {"camera.width=320", "camera.height=240"}},
            {"planet", {}},
            {"ringworld", {}},
            {"splash_droplets", {}},
            {"splash_sheet", {}},
            {"telescope", {}},
            // Real SPH output: the OpenSPH impact's middle frame (the target shattering under
            // the impactor, 9,574 particles of several smoothing lengths) at 320x240.
            {"collision_sequence",
             {"sequence.first=12", "sequence.last=12", "camera.width=320", "camera.height=240"}}};
}

std::string methodSeries(const MethodSweep& m, const std::string& shape) {
    return fmt::format("{}, {}", m.name, shape);
}

std::vector<std::string> methodSets(const MethodSweep& m, double value, const std::string& shape) {
    std::vector<std::string> sets = m.sets;
    if (m.key) sets.push_back(set(m.key, fmt::format("{:g}", value)));
    if (shape != "sphere") sets.push_back(set("realtime.particles.shape", "\"" + shape + "\""));
    return sets;
}

StudyPoint methodPoint(const MethodSweep& m, double x, const std::string& shape,
                       const std::string& scene, std::vector<std::string> more) {
    StudyPoint p{methodSeries(m, shape), x, methodSets(m, x, shape), scene};
    p.sets.insert(p.sets.end(), more.begin(), more.end());
    return p;
}

// On the default scenes, x is the method's parameter (0 for none); along particle size the
// pixels per particle (NaN here: particlePixels computes it), along view angle the degrees.
std::vector<StudyPoint> methodPoints(bool quick) {
    std::vector<StudyPoint> pts;
    for (const SuiteScene& scene : suiteScenes(quick))
        for (const std::string& shape : SHAPES)
            for (const MethodSweep& m : methodSweeps())
                for (double v : sweepValues(m, quick))
                    pts.push_back(
                        methodPoint(m, v, shape, "../" + scene.name + ".toml", scene.sets));
    // Quick: the largest and a small particle, face-on and grazing.
    const std::vector<double> distances =
        quick ? std::vector<double>{sizeDistances(true)[0], sizeDistances(true)[2]}
              : sizeDistances(false);
    const std::vector<double> angles =
        quick ? std::vector<double>{viewAngles(true).front(), viewAngles(true).back()}
              : viewAngles(false);
    for (const std::string& shape : SHAPES)
        for (const MethodSweep& m : methodSweeps())
            for (double d : distances) {
                StudyPoint p =
                    methodPoint(m, m.defaultValue, shape, SIZE_SCENE + ".toml", {sizeCamera(d)});
                if (quick) p.sets.push_back(SIZE_QUICK_PARTICLES);
                p.x = NAN;
                pts.push_back(std::move(p));
            }
    for (const std::string& shape : SHAPES)
        for (const MethodSweep& m : methodSweeps())
            for (double deg : angles) {
                StudyPoint p =
                    methodPoint(m, m.defaultValue, shape, ANGLE_SCENE + ".toml", angleCamera(deg));
                p.x = deg;
                pts.push_back(std::move(p));
            }
    // Quick: a coarse shadow map, the largest stage of these small frames on llvmpipe.
    if (quick)
        for (StudyPoint& p : pts) p.sets.push_back("realtime.shadow_map.resolution=256");
    return pts;
}

// "bilateral, sphere" -> {"bilateral", "sphere"}.
std::pair<std::string, std::string> methodAndShape(const std::string& series) {
    const auto comma = series.find(", ");
    if (comma == std::string::npos) return {series, ""};
    return {series.substr(0, comma), series.substr(comma + 2)};
}

const MethodSweep* sweepOf(const std::string& method) {
    static const std::vector<MethodSweep> all = methodSweeps();
    for (const MethodSweep& m : all)
        if (m.name == method) return &m;
    return nullptr;
}

// A shape other than spheres, as the labels name it: "" or " (ellipsoid)".
std::string shapeSuffix(const std::string& shape) {
    return shape.empty() || shape == "sphere" ? "" : " (" + shape + ")";
}

// "none", "ssss 0.6", "curvature_flow 40"; "ssss 0.6 (ellipsoid)" for another shape.
std::string settingLabel(const std::string& series, double x) {
    const auto [method, shape] = methodAndShape(series);
    const MethodSweep* m = sweepOf(method);
    return (m && m->key ? fmt::format("{} {:g}", method, x) : method) + shapeSuffix(shape);
}

std::string parameterText(const std::string& series, double x) {
    const MethodSweep* m = sweepOf(methodAndShape(series).first);
    if (!m || !m->key) return "";
    return fmt::format("{:g}{}", x, x == m->defaultValue ? " (default)" : "");
}

// "bilateral" for spheres, "bilateral (ellipsoid)" for another shape.
std::string methodName(const std::string& series) {
    const auto [method, shape] = methodAndShape(series);
    return method + shapeSuffix(shape);
}

// Per series in order of first appearance, its x -> normal.mean_deg over some rows (one
// scene's).
using NormalErrors = std::vector<std::pair<std::string, std::map<double, double>>>;
NormalErrors normalBySeries(const std::vector<const StudyRow*>& rows) {
    NormalErrors out;
    for (const StudyRow* r : rows) {
        if (!r->error.empty()) continue;
        auto it = std::find_if(out.begin(), out.end(),
                               [&](const auto& p) { return p.first == r->series; });
        if (it == out.end()) it = out.insert(out.end(), {r->series, {}});
        it->second[r->x] = metricOf(*r, "normal.mean_deg");
    }
    return out;
}
const std::map<double, double>* errorsOf(const NormalErrors& all, const std::string& series) {
    for (const auto& [name, errors] : all)
        if (name == series) return &errors;
    return nullptr;
}

// The series a method's series is measured against ("bilateral, sphere" -> "depth_normals,
// sphere"); "" for none.
std::string controlOf(const std::string& series) {
    const auto [method, shape] = methodAndShape(series);
    const MethodSweep* m = sweepOf(method);
    return m && !m->control.empty() ? fmt::format("{}, {}", m->control, shape) : "";
}

// The series of none with the same shape.
std::string noneOf(const std::string& series) {
    return fmt::format("{}, {}", realtime::toString(realtime::SurfaceMethod::None),
                       methodAndShape(series).second);
}

// A filter helps where it lowers the normal error against none by this fraction or more, and
// raises it where it is this fraction or more above none's.
constexpr double HELP_MARGIN = 0.10;

// Along particle size: where each method helps and where it raises the error against its
// control.
std::string sizeFinding(const std::vector<const StudyRow*>& rows, json& facts) {
    const auto normal = normalBySeries(rows);
    std::string out;
    for (const auto& [series, errors] : normal) {
        const auto* none = errorsOf(normal, controlOf(series));
        if (!none) continue;
        std::vector<double> helps, raises;
        json gains = json::object();
        for (const auto& [x, e] : errors) {
            const auto n = none->find(x);
            if (n == none->end()) continue;
            const double g = 1.0 - e / n->second;
            gains[fmt::format("{:.4g}", x)] = jsonOrNull(g);
            if (g >= HELP_MARGIN) helps.push_back(x);
            if (g <= -HELP_MARGIN) raises.push_back(x);
        }
        auto list = [](const std::vector<double>& xs) {
            std::string t;
            for (double x : xs) t += (t.empty() ? "" : ", ") + num(x);
            return t;
        };
        // Contiguous: every size between the smallest and the largest that helps helps too.
        bool contiguous = true;
        for (const auto& [x, e] : errors)
            if (!helps.empty() && x > helps.front() && x < helps.back() &&
                std::find(helps.begin(), helps.end(), x) == helps.end())
                contiguous = false;
        json& f = facts[series];
        f["control"] = controlOf(series);
        f["gain"] = gains;
        f["smallest_helping_px"] = helps.empty() ? json(nullptr) : json(helps.front());
        f["largest_helping_px"] = helps.empty() ? json(nullptr) : json(helps.back());
        f["raises_at_px"] = raises;
        std::string text = methodName(series);
        if (helps.empty())
            text += " at no size";
        else if (contiguous && helps.size() > 1)
            text += fmt::format(" from {} down to {} px", num(helps.back()), num(helps.front()));
        else
            text += fmt::format(" at {} px", list(helps));
        if (!raises.empty()) text += fmt::format(" (raises it at {} px)", list(raises));
        out += (out.empty() ? "" : ", ") + text;
    }
    return out;
}

// Along view angle: from which angle each method raises the error against its control for
// good, and its error face-on and at the largest angle.
std::string angleFinding(const std::vector<const StudyRow*>& rows, json& facts) {
    const auto normal = normalBySeries(rows);
    std::string raised, growth;
    for (const auto& [series, errors] : normal) {
        const auto* none = errorsOf(normal, controlOf(series));
        if (!none || errors.empty()) continue;
        double from = NAN;
        for (auto it = errors.rbegin(); it != errors.rend(); ++it) {
            const auto n = none->find(it->first);
            if (n == none->end() || !(1.0 - it->second / n->second <= -HELP_MARGIN)) break;
            from = it->first;
        }
        const std::string name = methodName(series);
        json& f = facts[series];
        f["control"] = controlOf(series);
        f["raises_from_deg"] = jsonOrNull(from);
        f["face_on_deg"] = jsonOrNull(errors.begin()->second);
        f["last_angle"] = errors.rbegin()->first;
        f["last_deg"] = jsonOrNull(errors.rbegin()->second);
        if (std::isfinite(from))
            raised += fmt::format("{}{} from {}°", raised.empty() ? "" : ", ", name, num(from));
        growth += fmt::format("{}{} {}° → {}°", growth.empty() ? "" : ", ", name,
                              num(errors.begin()->second), num(errors.rbegin()->second));
    }
    const double last = rows.empty() ? NAN : [&] {
        double a = -INFINITY;
        for (const StudyRow* r : rows) a = std::max(a, r->x);
        return a;
    }();
    return (raised.empty()
                ? fmt::format("no method raises the normal error above its control's up to {}°",
                              num(last))
                : "the normal error rises above the control's for " + raised) +
           fmt::format("; face-on → {}°: {}", num(last), growth);
}

report::LineChart alongChart(const std::vector<const StudyRow*>& rows, const std::string& title,
                             const std::string& xLabel, bool xLog) {
    report::LineChart c;
    c.title = title;
    c.xLabel = xLabel;
    c.yLabel = "normal.mean_deg (°)";
    c.xScale = xLog ? report::AxisScale::Log : report::AxisScale::Linear;
    for (const auto& [series, errors] : normalBySeries(rows)) {
        report::LineSeries line{series, {}, false};
        for (const auto& [x, e] : errors) line.points.push_back({x, e, ""});
        c.series.push_back(std::move(line));
    }
    return c;
}

// Stages in the order a frame runs them (realtime/README.md); others after them by name.
std::vector<std::string> stageOrder(const std::vector<report::SettingMedians>& settings) {
    std::set<std::string> seen;
    // A stage under 0.1 ms in every setting is per-particle-set work done in the warm-up frame.
    for (const auto& s : settings)
        for (const auto& [stage, ms] : s.timingsMs)
            if (ms >= 0.1) seen.insert(stage);
    return core::inStageOrder({seen.begin(), seen.end()});
}

double timeOf(const report::SettingMedians& s) {
    const auto it = s.timingsMs.find("total");
    return it == s.timingsMs.end() ? NAN : it->second;
}
double normalOf(const report::SettingMedians& s) {
    const auto it = s.metrics.find("normal.mean_deg");
    return it == s.metrics.end() ? NAN : it->second;
}

// The tables of the default scenes: the medians of every column and the frame time, the
// stages, the normal error per scene.
void suiteTables(StudyResult& s, const std::vector<report::SettingMedians>& settings,
                 const std::vector<std::size_t>& front, const std::vector<const StudyRow*>& rows,
                 const std::vector<std::string>& scenes) {
    const std::vector<std::string> labels = {"method", "parameter", "shape"};
    report::StudyTable summary{
        "summary",
        fmt::format("Per setting, the median over the {} default scenes of each metric and of the "
                    "real-time frame time (each point's time: the fastest of its frames); front: "
                    "on the Pareto front of time against normal.mean_deg.",
                    scenes.size()),
        {"method", "parameter", "shape", "front"},
        {},
        {}};
    for (const auto& c : s.columns)
        if (c != "count.unbracketed_rays") summary.columns.push_back(c);
    summary.columns.push_back("time.total_ms");
    report::StudyTable stages{
        "stages",
        "Per setting, the median over the default scenes of each stage's time of the real-time "
        "frame (the fastest of the point's frames), ms; stages under 0.1 ms in every setting, the "
        "per-particle-set work that the untimed first frame does, are left out.",
        labels,
        stageOrder(settings),
        {}};
    report::StudyTable byScene{"normal_by_scene",
                               "normal.mean_deg (°) per setting and default scene.",
                               labels,
                               scenes,
                               {}};
    for (std::size_t i = 0; i < settings.size(); ++i) {
        const auto& st = settings[i];
        const auto [method, shape] = methodAndShape(st.series);
        const std::vector<std::string> l = {method, parameterText(st.series, st.x), shape};
        report::StudyTable::Line line{l, {}};
        for (const auto& c : summary.columns)
            if (const auto it = st.metrics.find(c); it != st.metrics.end())
                line.values[c] = it->second;
        line.values["time.total_ms"] = timeOf(st);
        line.labels.push_back(std::find(front.begin(), front.end(), i) != front.end() ? "yes" : "");
        summary.lines.push_back(std::move(line));
        report::StudyTable::Line times{l, {}};
        for (const auto& stage : stages.columns)
            if (const auto it = st.timingsMs.find(stage); it != st.timingsMs.end())
                times.values[stage] = it->second;
        stages.lines.push_back(std::move(times));
        report::StudyTable::Line perScene{l, {}};
        for (const StudyRow* r : rows)
            if (r->series == st.series && r->x == st.x && r->error.empty())
                perScene.values[r->scene] = metricOf(*r, "normal.mean_deg");
        byScene.lines.push_back(std::move(perScene));
    }
    s.tables = {std::move(summary), std::move(stages), std::move(byScene)};
}

// normal.mean_deg along a study scene's x: a line per method, a column per x.
report::StudyTable alongTable(const std::string& file, const std::string& caption,
                              const std::vector<const StudyRow*>& rows,
                              const std::function<std::string(double)>& column) {
    report::StudyTable t{file, caption, {"method", "shape"}, {}, {}};
    std::set<double> xs;
    for (const StudyRow* r : rows) xs.insert(r->x);
    for (double x : xs) t.columns.push_back(column(x));
    for (const auto& [series, errors] : normalBySeries(rows)) {
        const auto [method, shape] = methodAndShape(series);
        report::StudyTable::Line line{{method, shape}, {}};
        for (const auto& [x, e] : errors) line.values[column(x)] = e;
        t.lines.push_back(std::move(line));
    }
    return t;
}

// The front, each step along it against the one before.
std::string frontFinding(const std::vector<report::SettingMedians>& settings,
                         const std::vector<std::size_t>& front, json& facts) {
    std::string text;
    facts = json::array();
    for (std::size_t k = 0; k < front.size(); ++k) {
        const auto& st = settings[front[k]];
        facts.push_back(settingLabel(st.series, st.x));
        text += fmt::format("{}{} ({} ms, {}°", k ? ", " : "", settingLabel(st.series, st.x),
                            num(timeOf(st)), num(normalOf(st)));
        if (k) {
            const auto& prev = settings[front[k - 1]];
            text += fmt::format(": {:+.0f} % error for {}x the time",
                                100.0 * (normalOf(st) / normalOf(prev) - 1.0),
                                num(timeOf(st) / timeOf(prev)));
        }
        text += ")";
    }
    return text;
}

// Each method at its default against none of its shape: its error and time over none's, and a
// depth filter's error over its control's.
std::string againstNoneFinding(const std::vector<report::SettingMedians>& settings, json& facts) {
    auto find = [&](const std::string& series) -> const report::SettingMedians* {
        for (const auto& o : settings)
            if (o.series == series) return &o;
        return nullptr;
    };
    std::string none, against;
    for (const auto& st : settings) {
        const std::string label = settingLabel(st.series, st.x);
        if (st.series == noneOf(st.series)) {
            none +=
                fmt::format("{}{}{}° at {} ms", none.empty() ? "" : ", ",
                            label == "none" ? "" : label + " ", num(normalOf(st)), num(timeOf(st)));
            continue;
        }
        const MethodSweep* m = sweepOf(methodAndShape(st.series).first);
        const auto* n = find(noneOf(st.series));
        if (!m || (m->key && st.x != m->defaultValue) || !n) continue;
        const double e = normalOf(st) / normalOf(*n), t = timeOf(st) / timeOf(*n);
        facts[label] = {{"normal_ratio", jsonOrNull(e)}, {"time_ratio", jsonOrNull(t)}};
        std::string versus = fmt::format("{}x {}", num(e), settingLabel(n->series, n->x));
        if (const auto* c = find(controlOf(st.series)); c && c != n) {
            facts[label]["control_normal_ratio"] = jsonOrNull(normalOf(st) / normalOf(*c));
            versus += fmt::format(", {}x {}", num(normalOf(st) / normalOf(*c)),
                                  settingLabel(c->series, c->x));
        }
        against += fmt::format("{}{} {}° ({}) at {}x the time", against.empty() ? "" : ", ", label,
                               num(normalOf(st)), versus, num(t));
    }
    return fmt::format("at their defaults against none ({}): {}", none, against);
}

// The chart of the default scenes: a point per setting, a colour per method and shape; and
// the settings as facts.
report::ScatterChart frontChart(const std::vector<report::SettingMedians>& settings,
                                const std::vector<std::size_t>& front, std::size_t scenes,
                                json& facts) {
    report::ScatterChart chart;
    chart.title =
        fmt::format("Surface methods: time against normal error, median over {} scenes", scenes);
    chart.xLabel = "real-time frame (ms): the fastest of its frames, median over the scenes";
    chart.yLabel = "normal.mean_deg (°), median over the scenes";
    // Room for a label beside each of the settings that crowd near the fastest frame.
    chart.width = 960;
    chart.height = 640;
    facts = json::array();
    for (std::size_t i = 0; i < settings.size(); ++i) {
        const auto& st = settings[i];
        const std::string label = settingLabel(st.series, st.x);
        chart.points.push_back({timeOf(st), normalOf(st), label});
        chart.groups.push_back(st.series);
        const auto [method, shape] = methodAndShape(st.series);
        facts.push_back({{"label", label},
                         {"series", st.series},
                         {"method", method},
                         {"shape", shape},
                         {"parameter", st.x},
                         {"scenes", st.scenes.size()},
                         {"time_ms", jsonOrNull(timeOf(st))},
                         {"normal_mean_deg", jsonOrNull(normalOf(st))},
                         {"on_front", std::find(front.begin(), front.end(), i) != front.end()}});
    }
    return chart;
}

// The figure and the table of the methods along a study scene's x.
void addAlong(StudyResult& s, const std::vector<const StudyRow*>& rows, const std::string& scene,
              const std::string& along, const std::string& xLabel, bool xLog,
              const std::function<std::string(double)>& column) {
    if (rows.empty()) return;
    s.figures.push_back(
        {scene,
         fmt::format("The normal error of each method at its defaults against {} ({} scene, the "
                     "impostors' sphere normals).",
                     along, scene),
         alongChart(rows, "Surface methods: normal error against " + along, xLabel, xLog)});
    s.tables.push_back(alongTable(
        scene,
        fmt::format("normal.mean_deg (°) per method at its defaults against {}, {} scene.", along,
                    scene),
        rows, column));
}

void methodsConclude(StudyResult& s) {
    std::vector<const StudyRow*> suite, size, angle;
    for (const StudyRow& r : s.rows)
        (r.scene == SIZE_SCENE ? size : r.scene == ANGLE_SCENE ? angle : suite).push_back(&r);
    std::vector<std::string> scenes;
    for (const StudyRow* r : suite)
        if (std::find(scenes.begin(), scenes.end(), r->scene) == scenes.end())
            scenes.push_back(r->scene);
    const auto settings = report::mediansOverScenes(suite);
    const auto front = report::settingsFront(settings, "normal.mean_deg");
    s.facts["scenes"] = scenes;
    s.facts["shapes"] = SHAPES;
    s.facts["aggregate"] = "median over the default scenes";
    s.scatter = frontChart(settings, front, scenes.size(), s.facts["settings"]);
    if (settings.empty()) {
        s.finding = "no render of the default scenes to compare";
        return;
    }
    s.finding = fmt::format(
        "on {} default scenes (medians), the Pareto front of frame time against normal error is "
        "{}; {}",
        scenes.size(), frontFinding(settings, front, s.facts["front"]),
        againstNoneFinding(settings, s.facts["against_none"]));
    if (!size.empty())
        s.finding +=
            "; along particle size, where each method's normal error is at least 10 % below its "
            "control's (none for ssss and depth_normals, depth_normals for the depth filters): " +
            sizeFinding(size, s.facts["particle_size"]);
    if (!angle.empty())
        s.finding += "; along view angle, " + angleFinding(angle, s.facts["view_angle"]);

    suiteTables(s, settings, front, suite, scenes);
    addAlong(s, size, SIZE_SCENE, "particle size", "particle diameter on screen (px)", true,
             [](double x) { return fmt::format("{:.3g} px", x); });
    addAlong(s, angle, ANGLE_SCENE, "view angle", "view angle from the surface normal (degrees)",
             false, [](double x) { return fmt::format("{:g}°", x); });
}

}  // namespace

report::LineChart seriesChart(const StudyResult& s, const std::string& metric) {
    report::LineChart c;
    // The x axis carries its own label: the title names the study and the metric only, so that
    // it fits over the plot.
    c.title = fmt::format("{}: {}", s.title, metric);
    c.xLabel = s.xLabel;
    const std::string unit = compare::metricUnit(metric);
    c.yLabel = unit.empty() ? metric : fmt::format("{} ({})", metric, unit);
    c.xScale = s.xLog ? report::AxisScale::Log : report::AxisScale::Linear;
    for (const auto& [name, rows] : bySeries(s)) {
        report::LineSeries line{name, {}, false};
        for (const StudyRow* r : rows) line.points.push_back({r->x, metricOf(*r, metric), ""});
        c.series.push_back(std::move(line));
    }
    return c;
}

namespace {

// Every metric a study charts or tabulates must be one of compare's metric table: a typo would
// show as an empty column.
std::vector<StudyDef> checked(std::vector<StudyDef> defs) {
    for (const StudyDef& d : defs) {
        std::vector<std::string> keys = d.columns;
        keys.push_back(d.metric);
        for (const std::string& k : keys)
            if (!compare::findMetric(k))
                throw std::logic_error(
                    fmt::format("study {}: '{}' is not in compare's metric table", d.name, k));
    }
    return defs;
}

}  // namespace

const std::vector<StudyDef>& studies() {
    // What the studies of the screen-space smoothing tabulate.
    const std::vector<std::string> smoothingColumns = {"normal.mean_deg", "normal.p95_deg",
                                                       "uv.mean",         "smoothness.ratio",
                                                       "beauty.flip",     "count.unbracketed_rays"};
    static const std::vector<StudyDef> all = checked({
        {"depth_range",
         "Depth range",
         "Far/near from 1e2 to 1e12 with the scene scaled along: where does each depth mode "
         "(standard 24-bit, reversed float, "
         "log) start to show the far body through the near one, or lose both (occlusion.error: the "
         "reference's covered pixels "
         "where the real-time render shows another body or none)?",
         "depth_range.toml",
         "far / near",
         true,
         "occlusion.error",
         {"occlusion.error", "id.mismatch", "coverage.iou", "depth.rel_mean", "beauty.flip",
          "count.unbracketed_rays"},
         false,
         true,
         false,
         1,
         depthPoints,
         nullptr,
         depthConclude},
        {"thin_casters",
         "Thin casters",
         "A ring one particle thick shadows its planet: shadow-map resolution and bias against "
         "shadow IoU, acne (false shadow) "
         "and leaks (missed shadow), with the per-body occlusion spheres beside them.",
         "thin_casters.toml",
         "shadow-map resolution (texels per side)",
         true,
         "shadow.iou",
         {"shadow.iou", "shadow.false_shadow", "shadow.missed_shadow", "beauty.flip",
          "count.unbracketed_rays"},
         false,
         false,
         false,
         1,
         shadowPoints,
         nullptr,
         shadowConclude},
        {"particle_size", "Particle size on screen",
         "The camera backs away from a slab from about 40 pixels per particle to below one: SSSS's "
         "normal and uv errors and "
         "smoothness, on and off; where does the filter radius selection stop helping?",
         "particle_size.toml", "particle diameter on screen (px)", true, "normal.mean_deg",
         smoothingColumns, false, false, false, 1, sizePoints, particlePixels, sizeConclude},
        {"view_angle", "View angle",
         "The camera turns from face-on to grazing over a flat slab: the view dependence of the "
         "screen-space smoothing.",
         "view_angle.toml", "view angle from the surface normal (degrees)", false,
         "normal.mean_deg", smoothingColumns, false, false, false, 1, anglePoints, nullptr,
         angleConclude},
        {"temporal",
         "Temporal stability",
         "A camera orbit in steps of half a degree: flicker as the mean frame-to-frame ꟻLIP of the "
         "real-time renders minus the "
         "reference's.",
         "temporal.toml",
         "frame",
         false,
         "temporal.frame_flip",
         {"temporal.frame_flip", "temporal.reference_frame_flip", "beauty.flip", "normal.mean_deg",
          "count.unbracketed_rays"},
         false,
         false,
         true,
         1,
         orbitPoints,
         nullptr,
         temporalConclude},
        {"flicker",
         "Flicker of the surface methods",
         "Which surface method flickers least against the truth (temporal.flicker: the "
         "real-time frames' frame-to-frame ꟻLIP minus the reference's) when SPH particles "
         "reorder: a ball whose particles churn (a new random displacement of up to 0.6 h each "
         "frame under a still surface), with the default particles and with impostor spheres, "
         "and the default suite's two real sequences, an OpenSPH impact and a LAMMPS splash, "
         "with the default particles.",
         "",
         "frame",
         false,
         "temporal.flicker",
         {"temporal.flicker", "temporal.frame_flip", "temporal.reference_frame_flip",
          "temporal.normal_flicker_deg", "normal.mean_deg", "beauty.flip",
          "count.unbracketed_rays"},
         false,
         false,
         true,
         1,
         flickerPoints,
         nullptr,
         flickerConclude},
        {"collision",
         "Two bodies colliding",
         "Two bodies from apart to overlapping: bleeding of uv and emission across the contact, "
         "measured in a 3-pixel band "
         "along the boundary between them in the reference.",
         "collision.toml",
         "gap between the surfaces (scene units; < 0 overlapping)",
         false,
         "contact.uv_mean",
         {"contact.uv_mean", "contact.emission_rmse", "contact.pixels", "uv.mean", "emission.rmse",
          "id.mismatch", "count.unbracketed_rays"},
         true,
         false,
         false,
         1,
         collisionPoints,
         nullptr,
         collisionConclude},
        {"methods",
         "Surface methods",
         "Every surface method at its defaults and along its main parameter, with each particle "
         "shape, on the default scenes and along particle size and view angle: how far each is "
         "from the exact surface (normals, depth, coverage, outlines, uv, ꟻLIP, smoothness) and "
         "what its frame costs (the fastest of 5 frames, rendered in rounds with the other "
         "settings of its scene after a warm-up frame).",
         "",
         "the method's parameter (particle radii; steps for curvature_flow); particle_size: "
         "px per particle; view_angle: degrees",
         false,
         "normal.mean_deg",
         {"normal.mean_deg", "normal.p95_deg", "depth.rel_mean", "coverage.iou",
          "silhouette.mean_px", "uv.mean", "beauty.flip", "smoothness.ratio",
          "count.unbracketed_rays"},
         false,
         false,
         false,
         5,
         methodPoints,
         particlePixels,
         methodsConclude},
    });
    return all;
}

}  // namespace twinrender::app
