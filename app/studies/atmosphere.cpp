// The atmosphere study (docs/studies.md): a planet with a thin atmosphere from filling the view
// to a few pixels across, each real-time end point's in-scatter against the reference's.
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "app/studies/common.h"
#include "app/studies/study_list.h"

namespace twinrender::app::study {

namespace {

// The camera's distances from the planet's centre, in its radii (quick: fewer, on a smaller
// image): from just above the limb (1.6: the planet fills the view) to about 4 pixels across.
std::vector<double> cameraDistances(bool quick) {
    return quick ? std::vector<double>{2.0, 8.0, 40.0}
                 : std::vector<double>{1.6, 2.0, 3.0, 5.0, 8.0, 13.0, 20.0, 40.0, 80.0};
}

// The time of the atmosphere pass in a row (the fastest of its frames); NaN without one.
double atmosphereTime(const StudyRow& r) {
    const auto it = r.timingsMs.find("atmosphere");
    return it == r.timingsMs.end() ? NAN : it->second;
}

}  // namespace

std::vector<StudyPoint> atmospherePoints(bool quick) {
    const double height = quick ? 48.0 : 120.0;  // the scene's, fov_y 40 degrees
    std::vector<StudyPoint> pts;
    for (const bool repeat : {false, true})
        for (const char* endPoint : {"impostor", "filtered", "sphere", "blend"})
            for (const double d : cameraDistances(quick)) {
                StudyPoint p{std::string(endPoint) + (repeat ? REPEAT : ""),
                             d,
                             {set("realtime.atmosphere.end_point", fmt::format("\"{}\"", endPoint)),
                              set("camera.position", vec(0.0, -d, 0.0))},
                             ""};
                if (repeat)
                    for (std::string& c : halfPixelAside(d, height, 40.0))
                        p.sets.push_back(std::move(c));
                if (quick) {
                    p.sets.push_back(set("camera.width", "64"));
                    p.sets.push_back(set("camera.height", "48"));
                    p.sets.push_back(set("bodies.planet.particles", "4000"));
                }
                pts.push_back(std::move(p));
            }
    return pts;
}

// At each distance the end points whose inscatter.rmse ties with the lowest (within the two
// rows' spreads, their difference from a render half a pixel aside) win; the finding gives each
// winner's (or tie's) run of distances: where one end point takes over from another, the
// thresholds a blend would set.
void atmosphereConclude(StudyResult& s) {
    s.chart = seriesChart(s, "inscatter.rmse");
    report::StudyTable table{
        "end_points",
        "Each end point at each camera distance (planet radii): the "
        "in-scatter's error against the reference's exact hit, its spread "
        "half a pixel aside, the image's HDR-ꟻLIP and the atmosphere pass's "
        "time.",
        {"series", "distance"},
        {"inscatter.rmse", "inscatter.spread", "inscatter.rel", "beauty.hdrflip", "atmosphere_ms"},
        {}};
    std::map<double, std::vector<Measured>> at;  // distance -> each end point's rmse
    for (const auto& [name, rows] : bySeries(s))
        for (const StudyRow* r : rows) {
            const double rmse = metricOf(*r, "inscatter.rmse");
            const double spread = spreadAt(s, *r, "inscatter.rmse");
            table.lines.push_back({{name, xNumber(r->x)},
                                   {{"inscatter.rmse", rmse},
                                    {"inscatter.spread", spread},
                                    {"inscatter.rel", metricOf(*r, "inscatter.rel")},
                                    {"beauty.hdrflip", metricOf(*r, "beauty.hdrflip")},
                                    {"atmosphere_ms", atmosphereTime(*r)}}});
            s.facts["rmse"][name][xNumber(r->x)] = jsonOrNull(rmse);
            s.facts["spread"][name][xNumber(r->x)] = jsonOrNull(spread);
            s.facts["rel"][name][xNumber(r->x)] = jsonOrNull(metricOf(*r, "inscatter.rel"));
            at[r->x].push_back({name, rmse, std::isfinite(spread) ? spread : 0.0});
        }
    s.tables.push_back(std::move(table));
    // The winners' runs along the distance: one end point, or several that tie.
    std::string finding;
    std::vector<std::string> current;
    double from = NAN, to = NAN;
    const auto flush = [&] {
        if (current.empty()) return;
        const std::string where = from == to
                                      ? fmt::format("at {}", xNumber(from))
                                      : fmt::format("from {} to {}", xNumber(from), xNumber(to));
        finding += fmt::format("{}{} {} {}", finding.empty() ? "" : "; ", joinNames(current),
                               current.size() == 1 ? "wins" : "tie", where);
        s.facts[current.size() == 1 ? "wins" : "ties"][joinNames(current)].push_back(
            {jsonOrNull(from), jsonOrNull(to)});
    };
    for (const auto& [x, measured] : at) {
        const std::vector<std::string> lowest = lowestOf(measured);
        s.facts["lowest"][xNumber(x)] = lowest;
        if (lowest.empty()) continue;
        if (lowest != current) {
            flush();
            if (!current.empty())
                s.chart.xMarks.push_back(
                    {x, joinNames(lowest) + (lowest.size() == 1 ? " takes over" : " take over")});
            current = lowest;
            from = x;
        }
        to = x;
    }
    flush();
    s.finding = finding.empty() ? "no rows to compare"
                                : "lowest inscatter.rmse along the camera's distance (planet "
                                  "radii), a tie within the spread of renders half a pixel "
                                  "aside: " +
                                      finding;
}

}  // namespace twinrender::app::study
