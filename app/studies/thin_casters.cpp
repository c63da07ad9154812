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
const std::string SHADOW_IOU = "shadow.iou";

// The smallest x from which every row of `rows` (sorted by x) ties with `target` or beats it:
// its shadow.iou not lower beyond the two rows' spreads (their difference from a render with
// the camera turned half a pixel); NaN when the finest does not.
double tiesFrom(const StudyResult& s, const std::vector<const StudyRow*>& rows,
                const StudyRow& target) {
    double from = NAN;
    for (auto it = rows.rbegin(); it != rows.rend(); ++it) {
        if (!std::isfinite(metricOf(**it, SHADOW_IOU)) ||
            orderOf(s, **it, target, SHADOW_IOU) == Order::Lower)
            break;
        from = (*it)->x;
    }
    return from;
}

// "esm from 256 texels (IoU 0.9 at 1024), ..." against PCF at its finest, and the facts.
std::string filtersAgainstPcf(const StudyResult& s, const SeriesRows& all, json& facts) {
    const auto* pcf = seriesRows(all, "pcf");
    if (!pcf || pcf->empty()) return "";
    const StudyRow& target = *pcf->back();
    std::string out;
    for (const char* filter : FILTERS) {
        const auto* rows = seriesRows(all, filter);
        if (!rows || rows->empty()) continue;
        const double from = tiesFrom(s, *rows, target);
        facts["filters"][filter] = {
            {"finest_iou", jsonOrNull(metricOf(*rows->back(), SHADOW_IOU))},
            {"finest_mae", jsonOrNull(metricOf(*rows->back(), "shadow.mae"))},
            {"matches_pcf_from", jsonOrNull(from)}};
        out += fmt::format("{}{} {} (IoU {} at {})", out.empty() ? "" : ", ", filter,
                           std::isfinite(from) ? "from " + xNumber(from) + " texels" : "never",
                           num(metricOf(*rows->back(), SHADOW_IOU)), xNumber(rows->back()->x));
    }
    return fmt::format("as good as pcf at {} texels (IoU {}, not lower beyond the noise): {}",
                       xNumber(target.x), num(metricOf(target, SHADOW_IOU)), out);
}

// The map series (hard shadow map, one per bias) in order of appearance.
std::vector<std::string> mapSeries(const SeriesRows& all) {
    std::vector<std::string> names;
    for (const auto& [name, rows] : all)
        if (name.rfind("map", 0) == 0 && !rows.empty()) names.push_back(name);
    return names;
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
    // Each again with the camera turned half a pixel: the noise the conclusion's ties rest on.
    addRepeats(pts);
    return pts;
}

void thinCastersConclude(StudyResult& s) {
    s.chart = seriesChart(s, SHADOW_IOU);
    for (auto& line : s.chart.series) line.dashed = line.name == "occlusion spheres";
    const auto all = bySeries(s);
    for (const auto& [name, rows] : all)
        for (const StudyRow* r : rows)
            s.facts["spread"][name][xNumber(r->x)] = jsonOrNull(spreadAt(s, *r, SHADOW_IOU));
    // The map series with the highest IoU at the finest resolution (and those that tie with
    // it), and from which resolution it ties with that.
    std::vector<Measured> finest;
    const StudyRow* best = nullptr;
    for (const std::string& name : mapSeries(all)) {
        const StudyRow* r = seriesRows(all, name)->back();
        finest.push_back(measuredOf(s, *r, SHADOW_IOU));
        if (std::isfinite(metricOf(*r, SHADOW_IOU)) &&
            (!best || metricOf(*r, SHADOW_IOU) > metricOf(*best, SHADOW_IOU)))
            best = r;
    }
    if (!best) {
        s.finding = "no shadow-map render to judge";
        return;
    }
    const auto& bestRows = *seriesRows(all, best->series);
    const std::vector<std::string> ties = highestOf(finest);
    const double enough = tiesFrom(s, bestRows, *best);
    const StudyRow* atEnough = best;
    for (const StudyRow* r : bestRows)
        if (r->x == enough) atEnough = r;
    const std::vector<std::string> maps = mapSeries(all);
    const auto& smallest = *seriesRows(all, maps.front());  // the smallest bias
    const auto& largest = *seriesRows(all, maps.back());
    const auto* spheres = seriesRows(all, "occlusion spheres");
    const double sphereIou = spheres ? meanOf(*spheres, SHADOW_IOU) : NAN;
    const Order spheresOrder =
        spheres && !spheres->empty() ? orderOf(s, *spheres->back(), *best, SHADOW_IOU) : Order::Tie;
    s.facts["best_series"] = best->series;
    s.facts["best_iou"] = metricOf(*best, SHADOW_IOU);
    s.facts["best_ties"] = ties;
    s.facts["enough_resolution"] = jsonOrNull(enough);
    s.facts["acne"] = jsonOrNull(metricOf(*smallest.back(), "shadow.false_shadow"));
    s.facts["leaks"] = jsonOrNull(metricOf(*largest.back(), "shadow.missed_shadow"));
    s.facts["spheres_iou"] = jsonOrNull(sphereIou);
    s.facts["spheres_against_best"] = orderName(spheresOrder);
    if (std::isfinite(enough)) s.chart.xMarks.push_back({enough, "as good as the best from"});
    std::vector<std::string> others;
    for (const std::string& name : ties)
        if (name != best->series) others.push_back(name);
    s.finding = fmt::format(
        "{} has the highest shadow.iou at {} texels, {}{}, and is as good (not lower beyond the "
        "noise: each row's difference from a render with the camera turned half a pixel) from "
        "{} texels ({}); {}: acne {} of the pixels facing the light; {}: leaks {}; occlusion "
        "spheres: IoU {}, {} the best map's",
        best->series, xNumber(best->x), num(metricOf(*best, SHADOW_IOU)),
        others.empty()
            ? ""
            : fmt::format(" ({} tie{} with it)", joinNames(others), others.size() == 1 ? "s" : ""),
        std::isfinite(enough) ? xNumber(enough) : std::string("no"),
        num(metricOf(*atEnough, SHADOW_IOU)), smallest.back()->series,
        percent(metricOf(*smallest.back(), "shadow.false_shadow")), largest.back()->series,
        percent(metricOf(*largest.back(), "shadow.missed_shadow")), num(sphereIou),
        spheresOrder == Order::Lower    ? "below"
        : spheresOrder == Order::Higher ? "above"
                                        : "a tie with");
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
    const std::string filters = filtersAgainstPcf(s, all, s.facts);
    if (!filters.empty()) s.finding += "; " + filters;
}

}  // namespace twinrender::app::study
