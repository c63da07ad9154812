// The ambient_occlusion study (docs/studies.md): the screen-space occlusion methods against the
// reference's traced occlusion on a ball resting on a slab, along their sample count, with the
// surface method, the blur and the noise each varied on the best method.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/studies/common.h"
#include "app/studies/study_list.h"
#include "report/svg_chart.h"

namespace twinrender::app::study {

namespace {

// A series: its name and the overrides beside the method's sample count.
struct AoSeries {
    std::string name;
    std::vector<std::string> sets;
};

std::vector<AoSeries> aoSeries() {
    const std::string gtao = "realtime.ao.method=\"gtao\"";
    return {
        {"ssao", {"realtime.ao.method=\"ssao\""}},
        {"hbao", {"realtime.ao.method=\"hbao\""}},
        {"gtao", {gtao}},
        // Does a surface method change the occlusion? The impostors' caps without smoothing,
        // and a depth filter, against SSSS (the default) above.
        {"gtao, no smoothing", {gtao, "realtime.surface.method=\"none\""}},
        {"gtao, bilateral depth", {gtao, "realtime.surface.method=\"bilateral\""}},
        // The blur: flat against depth-aware (the default) on the halo; none at all.
        {"gtao, flat blur", {gtao, "realtime.ao.blur=\"flat\""}},
        {"gtao, no blur", {gtao, "realtime.ao.blur=\"none\""}},
        // The noise under the blur: white and blue against interleaved gradient (the default).
        {"gtao, white noise", {gtao, "realtime.ao.noise=\"white\""}},
        {"gtao, blue noise", {gtao, "realtime.ao.noise=\"blue\""}},
        // Fewer channels: the normal + uv and emission in half floats (the seed's choice).
        {"gtao, compact G-buffer", {gtao, "realtime.gbuffer.format=\"compact\""}},
    };
}

// The occlusion methods crossed with the surface methods (the shader method aside: it has no
// filter of its own) at the methods' default 4 x 8 samples. The impostors' caps meet in
// creases that the smooth level set lacks: does a depth filter take away the false occlusion?
const std::vector<std::string> AO_METHODS = {"ssao", "hbao", "gtao"};

std::vector<std::string> crossSurfaces(bool quick) {
    if (quick) return {"ssss", "none"};
    return {"ssss", "bilateral", "narrow_range", "curvature_flow", "none"};
}

std::string crossSeries(const std::string& ao, const std::string& surface) {
    return ao + " on " + surface;
}

constexpr int CROSS_SAMPLES = 32;  // 4 slices x 8 steps, the methods' defaults

// The slices and steps of a point with `samples` samples per pixel: slices x steps, slices
// half the steps (at least 1) as the methods' defaults (4 x 8) have them.
std::pair<int, int> slicesAndSteps(int samples) {
    int slices = 1;
    while (2 * slices * 2 * slices * 2 <= samples) slices *= 2;
    return {slices, std::max(1, samples / slices)};
}

const StudyRow* bestOf(const std::vector<const StudyRow*>& rows, const std::string& metric) {
    const StudyRow* best = nullptr;
    for (const StudyRow* r : rows)
        if (std::isfinite(metricOf(*r, metric)) &&
            (!best || metricOf(*r, metric) < metricOf(*best, metric)))
            best = r;
    return best;
}

double aoTime(const StudyRow& r) {
    const auto it = r.timingsMs.find("ao");
    return it == r.timingsMs.end() ? NAN : it->second;
}

}  // namespace

std::vector<StudyPoint> ambientOcclusionPoints(bool quick) {
    const std::vector<int> samples =
        quick ? std::vector<int>{8, 32} : std::vector<int>{4, 8, 16, 32, 64, 128};
    std::vector<StudyPoint> pts;
    // Without occlusion: the error the methods start from, drawn across the axis.
    for (int n : {samples.front(), samples.back()})
        pts.push_back({"none", double(n), {"realtime.ao.method=\"none\""}, ""});
    for (const AoSeries& series : aoSeries())
        for (int n : samples) {
            const auto [slices, steps] = slicesAndSteps(n);
            StudyPoint p{series.name, double(slices * steps), series.sets, ""};
            p.sets.push_back(set("realtime.ao.slices", std::to_string(slices)));
            p.sets.push_back(set("realtime.ao.steps", std::to_string(steps)));
            pts.push_back(std::move(p));
        }
    for (const std::string& ao : AO_METHODS)
        for (const std::string& surface : crossSurfaces(quick))
            pts.push_back({crossSeries(ao, surface),
                           double(CROSS_SAMPLES),
                           {set("realtime.ao.method", "\"" + ao + "\""),
                            set("realtime.surface.method", "\"" + surface + "\"")},
                           ""});
    return pts;
}

void ambientOcclusionConclude(StudyResult& s) {
    s.chart = seriesChart(s, "ao.mean_abs");
    // The cross's points are one x each: a table below, not lines.
    std::erase_if(s.chart.series,
                  [](const auto& line) { return line.name.find(" on ") != std::string::npos; });
    for (auto& line : s.chart.series) line.dashed = line.name == "none";
    const auto all = bySeries(s);
    const auto* none = seriesRows(all, "none");
    const double noneError = none ? meanOf(*none, "ao.mean_abs") : NAN;
    // The cost against the error: every point, the Pareto front drawn.
    report::ScatterChart scatter;
    scatter.title = "Ambient occlusion: the pass's time against its error";
    scatter.xLabel = "ao pass (ms, one frame)";
    scatter.yLabel = "ao.mean_abs (lower is better)";
    json points = json::array();
    for (const StudyRow& r : s.rows) {
        if (r.series == "none" || !r.error.empty()) continue;
        scatter.points.push_back(
            {aoTime(r), metricOf(r, "ao.mean_abs"), fmt::format("{} {}", r.series, xNumber(r.x))});
        scatter.groups.push_back(r.series);
    }
    const std::vector<std::size_t> front = report::paretoFront(scatter.points, true);
    for (std::size_t i : front)
        points.push_back({{"label", scatter.points[i].label},
                          {"ao_ms", jsonOrNull(scatter.points[i].x)},
                          {"ao_mean_abs", jsonOrNull(scatter.points[i].y)}});
    s.facts["pareto_front"] = points;
    s.scatter = scatter;
    s.figures.push_back({"along_samples",
                         "ao.mean_abs along the samples per pixel (slices x steps), a line per "
                         "series; none dashed.",
                         s.chart});
    s.facts["none_mean_abs"] = jsonOrNull(noneError);
    std::string methods;
    for (const std::string name : {"ssao", "hbao", "gtao"}) {
        const auto* rows = seriesRows(all, name);
        const StudyRow* best = rows ? bestOf(*rows, "ao.mean_abs") : nullptr;
        if (!best) continue;
        s.facts[name] = {{"mean_abs", jsonOrNull(metricOf(*best, "ao.mean_abs"))},
                         {"bias", jsonOrNull(metricOf(*best, "ao.bias"))},
                         {"halo", jsonOrNull(metricOf(*best, "ao.halo"))},
                         {"samples", best->x}};
        methods += fmt::format("{}{} {} (bias {:+.3f}, halo {}) at {} samples",
                               methods.empty() ? "" : "; ", name,
                               num(metricOf(*best, "ao.mean_abs")), metricOf(*best, "ao.bias"),
                               num(metricOf(*best, "ao.halo")), xNumber(best->x));
    }
    // The variations of gtao at its largest sample count.
    std::string variations;
    for (const AoSeries& series : aoSeries()) {
        if (series.name.rfind("gtao, ", 0) != 0) continue;
        const auto* rows = seriesRows(all, series.name);
        if (!rows || rows->empty()) continue;
        const StudyRow& last = *rows->back();
        s.facts[series.name] = {{"mean_abs", jsonOrNull(metricOf(last, "ao.mean_abs"))},
                                {"halo", jsonOrNull(metricOf(last, "ao.halo"))}};
        variations +=
            fmt::format("{}{} {} (halo {})", variations.empty() ? "" : ", ", series.name.substr(6),
                        num(metricOf(last, "ao.mean_abs")), num(metricOf(last, "ao.halo")));
    }
    // A line per series at its largest sample count: the errors and the pass's cost.
    report::StudyTable table{
        "at_most_samples",
        "Each series at its largest sample count: the occlusion's errors against the traced "
        "truth and the ao pass's time (the fastest of the point's frames).",
        {"series", "samples"},
        {"ao.mean_abs", "ao.bias", "ao.halo", "ao.grain", "ao.banding", "normal.mean_deg",
         "uv.mean", "ao_ms"},
        {}};
    for (const auto& [name, rows] : all) {
        if (rows.empty()) continue;
        const StudyRow& last = *rows.back();
        table.lines.push_back({{name, xNumber(last.x)},
                               {{"ao.mean_abs", metricOf(last, "ao.mean_abs")},
                                {"ao.bias", metricOf(last, "ao.bias")},
                                {"ao.halo", metricOf(last, "ao.halo")},
                                {"ao.grain", metricOf(last, "ao.grain")},
                                {"ao.banding", metricOf(last, "ao.banding")},
                                {"normal.mean_deg", metricOf(last, "normal.mean_deg")},
                                {"uv.mean", metricOf(last, "uv.mean")},
                                {"ao_ms", aoTime(last)}}});
    }
    s.tables.push_back(std::move(table));
    // The cross: each occlusion method on each surface method.
    report::StudyTable cross{
        "by_surface",
        fmt::format("Each occlusion method on each surface method at {} samples (4 slices x 8 "
                    "steps): the occlusion's errors, the surface's normal error and the ao "
                    "pass's time.",
                    CROSS_SAMPLES),
        {"ao method", "surface method"},
        {"ao.mean_abs", "ao.bias", "ao.halo", "normal.mean_deg", "ao_ms"},
        {}};
    std::string byFilter;
    for (const std::string& ao : AO_METHODS) {
        double unsmoothed = NAN;
        std::vector<Measured> measured;
        for (const auto& [name, rows] : all) {
            if (rows.empty() || name.rfind(ao + " on ", 0) != 0) continue;
            const StudyRow& r = *rows.front();
            const std::string surface = name.substr(ao.size() + 4);
            const double e = metricOf(r, "ao.mean_abs");
            cross.lines.push_back({{ao, surface},
                                   {{"ao.mean_abs", e},
                                    {"ao.bias", metricOf(r, "ao.bias")},
                                    {"ao.halo", metricOf(r, "ao.halo")},
                                    {"normal.mean_deg", metricOf(r, "normal.mean_deg")},
                                    {"ao_ms", aoTime(r)}}});
            s.facts["by_surface"][ao][surface] = jsonOrNull(e);
            if (surface == "none") unsmoothed = e;
            // Every row is against one reference: two tie within its stated standard error,
            // half of it each row's noise.
            const double se = metricOf(r, "reference.ao_standard_error");
            measured.push_back({surface, e, std::isfinite(se) ? 0.5 * se : 0.0});
        }
        const std::vector<std::string> best = lowestOf(measured);
        if (best.empty()) continue;
        s.facts["by_surface"][ao]["best"] = best;
        const double bestError = s.facts["by_surface"][ao][best.front()].get<double>();
        const double se = 2.0 * measured.front().spread;
        byFilter += best.size() > 1 ? fmt::format(
                                          "{}{} {} on the bare impostors, {} tie (within the "
                                          "reference's standard error, {})",
                                          byFilter.empty() ? "" : "; ", ao, num(unsmoothed),
                                          joinNames(best), num(se))
                                    : fmt::format("{}{} {} on the bare impostors, {} on {}",
                                                  byFilter.empty() ? "" : "; ", ao, num(unsmoothed),
                                                  num(bestError), best.front());
    }
    s.tables.push_back(std::move(cross));
    // The noise kinds under the default blur at the fewest samples, where noise matters most.
    std::string noises;
    for (const auto& [label, name] :
         {std::pair<const char*, const char*>{"interleaved gradient", "gtao"},
          {"white", "gtao, white noise"},
          {"blue", "gtao, blue noise"}}) {
        const auto* rows = seriesRows(all, name);
        if (!rows || rows->empty()) continue;
        const StudyRow& first = *rows->front();
        s.facts["noise"][label] = {{"grain", jsonOrNull(metricOf(first, "ao.grain"))},
                                   {"banding", jsonOrNull(metricOf(first, "ao.banding"))},
                                   {"samples", first.x}};
        noises += fmt::format("{}{} {} / {}", noises.empty() ? "" : ", ", label,
                              num(metricOf(first, "ao.grain")), num(metricOf(first, "ao.banding")));
    }
    s.finding = fmt::format(
        "ao.mean_abs without occlusion {}; best of each method: {}; gtao at the most samples with "
        "one thing changed: {}; noise after the blur at the fewest samples (ao.grain / "
        "ao.banding): {}; each method on the surface methods at {} samples: {}",
        num(noneError), methods, variations, noises, CROSS_SAMPLES, byFilter);
}

}  // namespace twinrender::app::study
