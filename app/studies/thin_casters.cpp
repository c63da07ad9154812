// The thin_casters study (docs/studies.md): shadow-map resolution and bias under a thin ring.
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "app/studies/common.h"
#include "app/studies/study_list.h"

namespace twinrender::app::study {

namespace {
// The filtered series, PCF first: the others are judged against it.
constexpr const char* FILTERS[] = {"pcf", "esm", "vsm", "evsm"};

// The smallest x from which every row of `rows` (sorted by x) has shadow.iou of at least
// `target`; NaN when the finest does not.
double matchesFrom(const std::vector<const StudyRow*>& rows, double target) {
    double from = NAN;
    for (auto it = rows.rbegin(); it != rows.rend(); ++it) {
        if (!(metricOf(**it, "shadow.iou") >= target)) break;
        from = (*it)->x;
    }
    return from;
}

// "esm from 256 texels (IoU 0.9 at 1024), ..." against PCF at its finest, and the facts.
std::string filtersAgainstPcf(const SeriesRows& all, json& facts) {
    const auto* pcf = seriesRows(all, "pcf");
    if (!pcf || pcf->empty()) return "";
    const double target = metricOf(*pcf->back(), "shadow.iou") - 0.02;
    std::string out;
    for (const char* filter : FILTERS) {
        const auto* rows = seriesRows(all, filter);
        if (!rows || rows->empty()) continue;
        const double from = matchesFrom(*rows, target);
        facts["filters"][filter] = {
            {"finest_iou", jsonOrNull(metricOf(*rows->back(), "shadow.iou"))},
            {"finest_mae", jsonOrNull(metricOf(*rows->back(), "shadow.mae"))},
            {"matches_pcf_from", jsonOrNull(from)}};
        out += fmt::format("{}{} {} (IoU {} at {})", out.empty() ? "" : ", ", filter,
                           std::isfinite(from) ? "from " + xNumber(from) + " texels" : "never",
                           num(metricOf(*rows->back(), "shadow.iou")), xNumber(rows->back()->x));
    }
    return fmt::format("within 0.02 of pcf at {} texels: {}", xNumber(pcf->back()->x), out);
}
}  // namespace

std::vector<StudyPoint> thinCastersPoints(bool quick) {
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
    // The filtered maps and PCF at the default bias: at what map size does each match PCF at
    // the finest (the seed's claim: ESM let its map shrink from 2048 to 1024 texels)?
    for (const char* filter : FILTERS)
        for (int r : res)
            pts.push_back({filter,
                           double(r),
                           {set("realtime.shadows", fmt::format("\"{}\"", filter)),
                            set("realtime.shadow_map.resolution", std::to_string(r))},
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

void thinCastersConclude(StudyResult& s) {
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
    // A line per filtered series and resolution: the visibility's errors and the map's cost.
    report::StudyTable table{
        "filters",
        "PCF and the filtered maps at the default bias along the map's resolution: shadow IoU, "
        "mean visibility error, leaks into the umbra, and the shadow stage's time (one frame).",
        {"filter", "texels"},
        {"shadow.iou", "shadow.mae", "shadow.leak", "shadow_ms"},
        {}};
    for (const char* filter : FILTERS)
        if (const auto* rows = seriesRows(all, filter))
            for (const StudyRow* r : *rows) {
                const auto t = r->timingsMs.find("shadow");
                table.lines.push_back({{filter, xNumber(r->x)},
                                       {{"shadow.iou", metricOf(*r, "shadow.iou")},
                                        {"shadow.mae", metricOf(*r, "shadow.mae")},
                                        {"shadow.leak", metricOf(*r, "shadow.leak")},
                                        {"shadow_ms", t == r->timingsMs.end() ? NAN : t->second}}});
            }
    if (!table.lines.empty()) s.tables.push_back(std::move(table));
    const std::string filters = filtersAgainstPcf(all, s.facts);
    if (!filters.empty()) s.finding += "; " + filters;
}

}  // namespace twinrender::app::study
