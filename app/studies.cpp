#include "app/studies.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <numbers>
#include <stdexcept>

#include "compare/metric_table.h"
#include "compare/thresholds.h"

namespace twinrender::app {

namespace {

using compare::StudyResult;
using compare::StudyRow;
using nlohmann::json;

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
std::vector<StudyPoint> sizePoints(bool quick) {
    const std::vector<double> distances =
        quick ? std::vector<double>{0.55, 2.2, 8.8, 35.0}
              : std::vector<double>{0.37, 0.75, 1.5, 3.0, 6.0, 12.0, 25.0};
    const double a = 25.0 * std::numbers::pi / 180.0;
    std::vector<StudyPoint> pts;
    for (const bool ssss : {true, false})
        for (double d : distances)
            pts.push_back(
                {ssss ? "SSSS on" : "SSSS off",
                 NAN,
                 {set("realtime.ssss.enabled", ssss ? "true" : "false"),
                  set("camera.position", vec(0.0, -d * std::sin(a), 0.1 + d * std::cos(a)))},
                 ""});
    if (quick)
        for (auto& p : pts) p.sets.push_back("bodies.slab.particles=6000");
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

std::vector<StudyPoint> anglePoints(bool quick) {
    const std::vector<double> angles =
        quick ? std::vector<double>{0, 45, 80} : std::vector<double>{0, 15, 30, 45, 60, 70, 80, 85};
    std::vector<StudyPoint> pts;
    for (const bool ssss : {true, false})
        for (double deg : angles) {
            const double a = deg * std::numbers::pi / 180.0, d = 3.0;
            pts.push_back(
                {ssss ? "SSSS on" : "SSSS off",
                 deg,
                 {set("realtime.ssss.enabled", ssss ? "true" : "false"),
                  set("camera.position", vec(0.0, -d * std::sin(a), 0.1 + d * std::cos(a))),
                  // Perpendicular to the view direction at every angle.
                  set("camera.up", vec(0.0, std::cos(a), std::sin(a)))},
                 ""});
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
        compare::LineSeries ref{"reference", {}, true};
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

}  // namespace

compare::LineChart seriesChart(const StudyResult& s, const std::string& metric) {
    compare::LineChart c;
    // The x axis carries its own label: the title names the study and the metric only, so that
    // it fits over the plot.
    c.title = fmt::format("{}: {}", s.title, metric);
    c.xLabel = s.xLabel;
    const std::string unit = compare::metricUnit(metric);
    c.yLabel = unit.empty() ? metric : fmt::format("{} ({})", metric, unit);
    c.xScale = s.xLog ? compare::AxisScale::Log : compare::AxisScale::Linear;
    for (const auto& [name, rows] : bySeries(s)) {
        compare::LineSeries line{name, {}, false};
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
    });
    return all;
}

}  // namespace twinrender::app
