// The atmosphere study (docs/studies.md): a planet with a thin atmosphere from filling the view
// to a few pixels across, each real-time end point's in-scatter against the reference's.
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <string>
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
    std::vector<StudyPoint> pts;
    for (const char* endPoint : {"impostor", "filtered", "sphere", "blend"})
        for (const double d : cameraDistances(quick)) {
            StudyPoint p{endPoint,
                         d,
                         {set("realtime.atmosphere.end_point", fmt::format("\"{}\"", endPoint)),
                          set("camera.position", vec(0.0, -d, 0.0))},
                         ""};
            if (quick) {
                p.sets.push_back(set("camera.width", "64"));
                p.sets.push_back(set("camera.height", "48"));
                p.sets.push_back(set("bodies.planet.particles", "4000"));
            }
            pts.push_back(std::move(p));
        }
    return pts;
}

// At each distance the end point with the lowest inscatter.rmse wins; the finding gives each
// winner's run of distances (where one end point takes over from another: the thresholds a
// blend would set) and the error of the sphere's and the impostors' there.
void atmosphereConclude(StudyResult& s) {
    s.chart = seriesChart(s, "inscatter.rmse");
    report::StudyTable table{"end_points",
                             "Each end point at each camera distance (planet radii): the "
                             "in-scatter's error against the reference's exact hit, the image's "
                             "HDR-ꟻLIP and the atmosphere pass's time.",
                             {"series", "distance"},
                             {"inscatter.rmse", "inscatter.rel", "beauty.hdrflip", "atmosphere_ms"},
                             {}};
    std::map<double, std::pair<std::string, double>> best;  // distance -> (series, rmse)
    for (const auto& [name, rows] : bySeries(s))
        for (const StudyRow* r : rows) {
            const double rmse = metricOf(*r, "inscatter.rmse");
            table.lines.push_back({{name, xNumber(r->x)},
                                   {{"inscatter.rmse", rmse},
                                    {"inscatter.rel", metricOf(*r, "inscatter.rel")},
                                    {"beauty.hdrflip", metricOf(*r, "beauty.hdrflip")},
                                    {"atmosphere_ms", atmosphereTime(*r)}}});
            s.facts["rmse"][name][xNumber(r->x)] = jsonOrNull(rmse);
            s.facts["rel"][name][xNumber(r->x)] = jsonOrNull(metricOf(*r, "inscatter.rel"));
            if (!std::isfinite(rmse)) continue;
            auto it = best.find(r->x);
            if (it == best.end() || rmse < it->second.second) best[r->x] = {name, rmse};
        }
    s.tables.push_back(std::move(table));
    // The winners' runs along the distance.
    std::string finding;
    std::string current;
    double from = NAN, to = NAN;
    const auto flush = [&] {
        if (current.empty()) return;
        finding +=
            fmt::format("{}{} wins {}", finding.empty() ? "" : "; ", current,
                        from == to ? fmt::format("at {}", xNumber(from))
                                   : fmt::format("from {} to {}", xNumber(from), xNumber(to)));
        s.facts["wins"][current].push_back({jsonOrNull(from), jsonOrNull(to)});
    };
    for (const auto& [x, winner] : best) {
        if (winner.first != current) {
            flush();
            if (!current.empty()) s.chart.xMarks.push_back({x, winner.first + " takes over"});
            current = winner.first;
            from = x;
        }
        to = x;
    }
    flush();
    s.finding = finding.empty() ? "no rows to compare"
                                : "lowest inscatter.rmse along the camera's distance (planet "
                                  "radii): " +
                                      finding;
}

}  // namespace twinrender::app::study
