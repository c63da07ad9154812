// The flicker study (docs/studies.md): which surface method flickers least against the truth.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "app/studies/common.h"
#include "app/studies/study_list.h"

namespace twinrender::app::study {

namespace {

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

// A mean as the finding writes it: two significant digits and its sign ("+0.0003", "-4.3");
// "unmeasured" when there is none.
std::string signedNum(const json& v) {
    if (!v.is_number()) return "unmeasured";
    const double x = v.get<double>();
    return x == 0.0 ? "0" : fmt::format("{:+.2g}", x);
}

std::string flickerSeries(const std::string& method, const FlickerGroup& g) {
    return fmt::format("{} ({})", method, g.name);
}

}  // namespace

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
        std::vector<Measured> measured;
        for (const char* method : FLICKER_METHODS) {
            const std::string name = flickerSeries(method, g);
            const auto* rows = seriesRows(all, name);
            if (!rows) continue;
            const double v = meanOf(*rows, metric), n = meanOf(*rows, normal);
            s.facts["flicker"][name] = jsonOrNull(v);
            s.facts["normal_flicker_deg"][name] = jsonOrNull(n);
            // The noise of a mean over frames: its standard error.
            const double se = standardErrorOf(*rows, metric);
            s.facts["flicker_standard_error"][name] = jsonOrNull(se);
            table.lines.push_back({{g.name, method}, {{metric, v}, {normal, n}}});
            measured.push_back({method, v, std::isfinite(se) ? se : 0.0});
            report::LineSeries line{
                g.legend.empty() ? method : fmt::format("{} ({})", method, g.legend),
                {},
                !g.legend.empty()};
            for (const StudyRow* r : *rows) line.points.push_back({r->x, metricOf(*r, metric), ""});
            chart.series.push_back(std::move(line));
        }
        // The least and the most, with those that tie with them within the two means'
        // standard errors; each one's numbers in the finding.
        const std::vector<std::string> least = lowestOf(measured), most = highestOf(measured);
        const auto numbers = [&](const std::vector<std::string>& methods) {
            std::vector<std::string> each;
            for (const std::string& m : methods) {
                const std::string name = flickerSeries(m, g);
                each.push_back(fmt::format("{} ({}, {}°)", m, signedNum(s.facts["flicker"][name]),
                                           signedNum(s.facts["normal_flicker_deg"][name])));
            }
            return (each.size() > 1 ? "a tie of " : "") + joinNames(each);
        };
        s.facts["groups"][g.name] = {{"least", least}, {"most", most}};
        parts += fmt::format("{}{}: least {}, most {}", parts.empty() ? "" : "; ", g.name,
                             numbers(least), numbers(most));
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
        const json churn = s.facts["groups"][CHURN].value("least", json::array());
        agree +=
            fmt::format("{}{} {}", agree.empty() ? "" : ", ", g.name,
                        json(least) == churn ? "agrees" : "differs (" + joinNames(least) + ")");
    }
    s.tables.push_back(std::move(table));
    s.finding = fmt::format(
        "flicker against the truth (mean real-time minus reference frame-to-frame ꟻLIP, and of "
        "the normal; below 0 a method changes less than the truth does): {}; against the "
        "churning ball's least, {}",
        parts, agree);
}

}  // namespace twinrender::app::study
