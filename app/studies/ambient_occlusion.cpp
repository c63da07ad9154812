// The ambient_occlusion study (docs/studies.md): the real-time occlusion methods (screen-space,
// and rays traced against the particles' spheres) against the reference's traced occlusion along
// the occlusion radius R, on a ball resting on a slab and on two scenes with a gap the truth
// leaves open at small R (a ball hanging over a slab, two balls apart), each method on the shaded
// and the filtered depth, with and without a thickness or a second depth layer, and on a
// depth-filtering surface method. The finding says where each setting helps and where it hurts
// against no occlusion, deciding with the spread of renders half a pixel aside.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "app/studies/common.h"
#include "app/studies/study_list.h"
#include "realtime/settings.h"
#include "report/study_summary.h"
#include "report/svg_chart.h"

namespace twinrender::app::study {

namespace {

// The radius of every ball of the study's scenes (scene units): R is counted in it.
constexpr double BODY_RADIUS = 0.4;
// The bound on false occlusion a recommended method may add where the truth is open (ao.false,
// a fraction of the ambient), and the radius (body radii) from which it must lower the error
// against no occlusion wherever the truth is occluded.
constexpr double FALSE_BOUND = 0.005;
constexpr double GAIN_FROM_R = 1.0;

// A scene of the study: its file in scenes/studies/, its name (its rows' scene) and its camera,
// which every point sets (its repeat half a pixel aside).
struct AoScene {
    const char* file;
    const char* name;
    CameraPose camera;
};

const std::vector<AoScene>& aoScenes() {
    static const std::vector<AoScene> scenes = {
        {"ambient_occlusion.toml",
         "ball_on_slab",
         {.position = {-1.7, -1.9, 1.5}, .target = {0.0, 0.0, 0.2}, .up = {0.0, 0.0, 1.0}}},
        {"ambient_occlusion_over.toml",
         "ball_over_slab",
         {.position = {-1.7, -1.9, 2.3}, .target = {0.0, 0.0, 0.5}, .up = {0.0, 0.0, 1.0}}},
        {"ambient_occlusion_apart.toml",
         "balls_apart",
         {.position = {0.6, -3.4, 0.5}, .target = {0.0, 0.0, 0.0}, .up = {0.0, 0.0, 1.0}}},
    };
    return scenes;
}

constexpr double AO_SCENES_FOV_Y_DEG = 40.0;  // every study scene's

// The radii, in body radii (quick: fewer, on a smaller image with fewer traced directions).
std::vector<double> radii(bool quick) {
    return quick ? std::vector<double>{0.25, 1.0, 4.0}
                 : std::vector<double>{0.25, 0.5, 1.0, 1.5, 2.0, 3.0, 5.0, 10.0};
}

// gtao's angle bias in the study's settings (degrees), and the series without one.
constexpr double GTAO_BIAS = 10.0;

// A setting of the occlusion pass: the method, the depth it reads, the thickness of each
// occluder (particle radii) and the surface method; each point sets them all, so that a series
// keeps its meaning when a default changes.
struct AoSetting {
    std::string method;  // "none", "ssao", "hbao", "gtao", "traced"
    std::string depth = "shaded";
    double thickness = 0.0;
    int layers = 1;               // ao.layers
    double gtaoBias = GTAO_BIAS;  // ao.gtao_angle_bias, degrees
    std::string surface = "ssss";
    bool quick = true;  // in quick runs too

    std::string name() const {
        if (method == "none") return "none";
        if (surface != "ssss") return method + " on " + surface;
        return fmt::format("{}, {} depth{}{}{}", method, depth,
                           thickness > 0.0 ? fmt::format(", thickness {}", thickness) : "",
                           layers == 2 ? ", second layer" : "",
                           method == "gtao" && gtaoBias != GTAO_BIAS
                               ? fmt::format(", angle bias {}", gtaoBias)
                               : "");
    }
};

const std::vector<std::string> AO_METHODS = {"ssao", "hbao", "gtao", "traced"};

std::vector<AoSetting> aoSettings(bool quick) {
    std::vector<AoSetting> all = {{.method = "none"}};
    for (const std::string& m : AO_METHODS) {
        all.push_back({.method = m, .depth = "shaded"});
        all.push_back({.method = m, .depth = "filtered"});
        // The traced rays meet the spheres themselves: no thickness to guess, and the depth
        // only places the rays' origins.
        if (m == "traced") continue;
        all.push_back({.method = m, .depth = "shaded", .thickness = 4.0, .quick = false});
        all.push_back({.method = m, .depth = "filtered", .thickness = 4.0});
        // The second depth layer: in quick runs for gtao alone, the method whose bit mask
        // integrates an occluder's span.
        all.push_back({.method = m, .depth = "filtered", .layers = 2, .quick = m == "gtao"});
        // gtao without its angle bias, as published.
        if (m == "gtao") {
            all.push_back({.method = m, .depth = "filtered", .gtaoBias = 0.0, .quick = false});
            all.push_back(
                {.method = m, .depth = "filtered", .layers = 2, .gtaoBias = 0.0, .quick = false});
        }
        // A surface method that filters the depth itself: the occlusion and the shade pass
        // read the same filtered depth.
        all.push_back({.method = m, .surface = "curvature_flow", .quick = false});
    }
    std::erase_if(all, [&](const AoSetting& a) { return quick && !a.quick; });
    return all;
}

// The series of the occlusion pass at the code's defaults for `method` (ao.depth and
// ao.thickness as realtime::AoSettings has them, the default surface method); "" when the
// study has no such series.
std::string defaultSeries(const std::string& method) {
    const realtime::AoSettings d;
    const std::string depth(realtime::toString(d.depth));
    for (const AoSetting& a : aoSettings(false))
        if (a.method == method && a.surface == "ssss" && a.depth == depth &&
            a.thickness == d.thickness && a.layers == d.layers &&
            (method != "gtao" || a.gtaoBias == d.gtaoAngleBiasDeg))
            return a.name();
    return "";
}

// One setting at one scene and R: what the conclusion reads of its row and its repeat's.
struct AoCell {
    double meanAbs = NAN, meanAbsSpread = NAN;  // ao.mean_abs, its spread half a pixel aside
    double falseOcclusion = NAN, falseSpread = NAN;
    double missed = NAN;         // NaN: the truth has no occluded pixel (open)
    double standardError = NAN;  // the reference's, per pixel
    double aoMs = NAN;
};
// scene -> setting -> R -> its cell.
using AoCells = std::map<std::string, std::map<std::string, std::map<double, AoCell>>>;

// The rows of one scene, as a study of its own (the shared helpers group by series).
StudyResult aoSceneOnly(const StudyResult& s, const std::string& scene) {
    StudyResult out;
    out.title = s.title;
    out.xLabel = s.xLabel;
    out.xLog = s.xLog;
    for (const StudyRow& r : s.rows)
        if (r.scene == scene && r.error.empty()) out.rows.push_back(r);
    return out;
}

double aoTime(const StudyRow& r) {
    const auto it = r.timingsMs.find("ao");
    return it == r.timingsMs.end() ? NAN : it->second;
}

AoCells cellsOf(const StudyResult& s) {
    AoCells cells;
    for (const AoScene& scene : aoScenes()) {
        const StudyResult one = aoSceneOnly(s, scene.name);
        for (const auto& [name, rows] : bySeries(one))
            for (const StudyRow* r : rows)
                cells[scene.name][name][r->x] = {
                    .meanAbs = metricOf(*r, "ao.mean_abs"),
                    .meanAbsSpread = spreadAt(one, *r, "ao.mean_abs"),
                    .falseOcclusion = metricOf(*r, "ao.false"),
                    .falseSpread = spreadAt(one, *r, "ao.false"),
                    .missed = metricOf(*r, "ao.missed"),
                    .standardError = metricOf(*r, "reference.ao_standard_error"),
                    .aoMs = aoTime(*r)};
    }
    return cells;
}

double aoOrZero(double v) {
    return std::isfinite(v) ? v : 0.0;
}

// "ball_over_slab at R 3".
std::string atScene(const std::string& scene, double r) {
    return fmt::format("{} at R {}", scene, xNumber(r));
}

// A point where one setting's ao.mean_abs stands against another's: its scene, R and the
// difference (the first's minus the second's).
struct AoPoint {
    std::string scene;
    double r = NAN, delta = NAN;
};
// Points sorted by how the first setting stands: lower, tied (within the two cells' spreads) or
// higher.
struct AoAgainst {
    std::vector<AoPoint> lower, tie, higher;
    void add(const AoCell& a, const AoCell& b, const std::string& scene, double r) {
        const AoPoint p{scene, r, a.meanAbs - b.meanAbs};
        switch (
            order(a.meanAbs, b.meanAbs, aoOrZero(a.meanAbsSpread) + aoOrZero(b.meanAbsSpread))) {
            case Order::Lower:
                lower.push_back(p);
                break;
            case Order::Tie:
                tie.push_back(p);
                break;
            case Order::Higher:
                higher.push_back(p);
                break;
        }
    }
};

json aoPointsJson(const std::vector<AoPoint>& points) {
    json out = json::array();
    for (const AoPoint& p : points)
        out.push_back({{"scene", p.scene}, {"r", p.r}, {"delta", jsonOrNull(p.delta)}});
    return out;
}

// One setting over every scene and R: its largest false occlusion and where, whether it passes
// the bound, and against none from GAIN_FROM_R where the truth is occluded.
struct AoVerdict {
    double worstFalse = NAN, worstFalseR = NAN;
    std::string worstFalseScene;
    bool exceedsBound = false;  // some ao.false above FALSE_BOUND by more than its spread
    AoAgainst none;
    double aoMs = NAN;  // the median of its cells' ao pass time
    bool meets() const {
        return !exceedsBound && none.tie.empty() && none.higher.empty() && !none.lower.empty();
    }
};

AoVerdict verdictOf(const AoCells& cells, const std::string& name) {
    AoVerdict v;
    std::vector<double> times;
    for (const auto& [scene, settings] : cells) {
        const auto it = settings.find(name);
        const auto none = settings.find("none");
        if (it == settings.end()) continue;
        for (const auto& [r, c] : it->second) {
            times.push_back(c.aoMs);
            if (std::isfinite(c.falseOcclusion) && !(c.falseOcclusion <= v.worstFalse)) {
                v.worstFalse = c.falseOcclusion;
                v.worstFalseScene = scene;
                v.worstFalseR = r;
            }
            if (order(c.falseOcclusion, FALSE_BOUND, aoOrZero(c.falseSpread)) == Order::Higher)
                v.exceedsBound = true;
            if (r < GAIN_FROM_R || none == settings.end() || !none->second.contains(r)) continue;
            const AoCell& n = none->second.at(r);
            if (std::isfinite(n.missed)) v.none.add(c, n, scene, r);
        }
    }
    v.aoMs = report::median(times);
    return v;
}

// How a setting that does not meet the goal misses it: "hbao, filtered depth (12 of 14 lower)"
// within the bound, "gtao, filtered depth, second layer (ao.false 0.0055 ball_on_slab at R
// 0.25)" lower everywhere; "" for one that misses both.
std::string missText(const std::string& name, const AoVerdict& v) {
    const AoAgainst& a = v.none;
    const std::size_t points = a.lower.size() + a.tie.size() + a.higher.size();
    if (!v.exceedsBound) return fmt::format("{} ({} of {} lower)", name, a.lower.size(), points);
    if (a.tie.empty() && a.higher.empty() && !a.lower.empty())
        return fmt::format("{} (ao.false {} {})", name, num(v.worstFalse),
                           atScene(v.worstFalseScene, v.worstFalseR));
    return "";
}

// One option against another (the filtered depth against the shaded, a thickness against none)
// on one method and scene: the points where it is lower, tied or higher, and over the scene's
// radii the mean difference and the mean of the two spreads. Better on the scene: that mean
// difference below minus that mean spread.
struct AoOptionOnScene {
    AoAgainst points;
    double meanDelta = NAN, meanNoise = NAN;
    bool better() const { return order(meanDelta, 0.0, meanNoise) == Order::Lower; }
};

AoOptionOnScene optionOnScene(const std::map<double, AoCell>& with,
                              const std::map<double, AoCell>& without, const std::string& scene) {
    AoOptionOnScene o;
    double delta = 0.0, noise = 0.0;
    int n = 0;
    for (const auto& [r, a] : with) {
        const auto b = without.find(r);
        if (b == without.end() || !std::isfinite(a.meanAbs) || !std::isfinite(b->second.meanAbs))
            continue;
        o.points.add(a, b->second, scene, r);
        delta += a.meanAbs - b->second.meanAbs;
        noise += aoOrZero(a.meanAbsSpread) + aoOrZero(b->second.meanAbsSpread);
        ++n;
    }
    if (n > 0) {
        o.meanDelta = delta / n;
        o.meanNoise = noise / n;
    }
    return o;
}

// An option of the occlusion pass as a default would set it: each method's setting with it and
// without it.
struct AoOption {
    std::string name;           // "ao.depth filtered"
    std::string with, without;  // the settings' names with "{}" for the method
};

const std::vector<AoOption>& aoOptions() {
    static const std::vector<AoOption> options = {
        {"ao.depth filtered", "{}, filtered depth", "{}, shaded depth"},
        {"ao.thickness 4 on the filtered depth", "{}, filtered depth, thickness 4",
         "{}, filtered depth"},
        {"ao.thickness 4 on the shaded depth", "{}, shaded depth, thickness 4", "{}, shaded depth"},
        {"ao.layers 2 on the filtered depth", "{}, filtered depth, second layer",
         "{}, filtered depth"},
        {"ao.gtao_angle_bias 10 on the filtered depth", "{}, filtered depth",
         "{}, filtered depth, angle bias 0"},
        {"ao.gtao_angle_bias 10 with the second layer", "{}, filtered depth, second layer",
         "{}, filtered depth, second layer, angle bias 0"},
    };
    return options;
}

// The option on every method and scene: facts, and a sentence saying where it is better and
// where it harms.
std::string optionText(const AoCells& cells, const AoOption& option, json& facts) {
    std::vector<std::string> every, some, none;  // the methods it is better for on those scenes
    for (const std::string& m : AO_METHODS) {
        const std::string with = fmt::format(fmt::runtime(option.with), m);
        const std::string without = fmt::format(fmt::runtime(option.without), m);
        std::vector<std::string> better, worse;
        for (const auto& [scene, settings] : cells) {
            const auto a = settings.find(with), b = settings.find(without);
            if (a == settings.end() || b == settings.end()) continue;
            const AoOptionOnScene o = optionOnScene(a->second, b->second, scene);
            facts[m][scene] = {
                {"lower", aoPointsJson(o.points.lower)},   {"tie", aoPointsJson(o.points.tie)},
                {"higher", aoPointsJson(o.points.higher)}, {"mean_delta", jsonOrNull(o.meanDelta)},
                {"mean_noise", jsonOrNull(o.meanNoise)},   {"better", o.better()}};
            (o.better() ? better : worse).push_back(scene);
        }
        if (better.empty() && worse.empty()) continue;
        facts[m]["better_on_every_scene"] = worse.empty();
        (worse.empty()    ? every
         : better.empty() ? none
                          : some)
            .push_back(worse.empty() || better.empty()
                           ? m
                           : fmt::format("{} (not on {})", m, joinNames(worse)));
    }
    if (every.empty() && some.empty() && none.empty()) return "";
    std::string text = option.name + ":";
    if (!every.empty()) text += " better on every scene for " + joinNames(every);
    if (!some.empty())
        text += std::string(every.empty() ? "" : ",") + " on some for " + joinNames(some);
    if (!none.empty())
        text += std::string(every.empty() && some.empty() ? "" : ",") + " on none for " +
                joinNames(none);
    return text;
}

// The lines of a chart of `metric` along R on one scene, none dashed.
report::LineChart sceneChart(const StudyResult& one, const std::string& scene,
                             const std::string& metric) {
    report::LineChart c = seriesChart(one, metric);
    c.title = fmt::format("Ambient occlusion on {}: {}", scene, metric);
    for (auto& line : c.series) line.dashed = line.name == "none";
    return c;
}

}  // namespace

std::vector<StudyPoint> ambientOcclusionPoints(bool quick) {
    const double height = quick ? 72.0 : 96.0;
    // What quick runs add: a smaller image, fewer traced directions.
    const std::vector<std::string> smaller =
        quick ? std::vector<std::string>{set("camera.width", "96"), set("camera.height", "72"),
                                         set("raymarch.ao_samples", "64")}
              : std::vector<std::string>{};
    std::vector<StudyPoint> pts;
    for (const AoScene& scene : aoScenes())
        for (const bool repeat : {false, true})
            for (const AoSetting& a : aoSettings(quick))
                for (const double r : radii(quick)) {
                    StudyPoint p{a.name() + (repeat ? REPEAT : ""),
                                 r,
                                 {set("light.ao_radius", fmt::format("{:.9g}", r * BODY_RADIUS)),
                                  set("realtime.ao.method", "\"" + a.method + "\""),
                                  set("realtime.ao.depth", "\"" + a.depth + "\""),
                                  set("realtime.ao.thickness", fmt::format("{}", a.thickness)),
                                  set("realtime.ao.layers", fmt::format("{}", a.layers)),
                                  set("realtime.ao.gtao_angle_bias", fmt::format("{}", a.gtaoBias)),
                                  set("realtime.surface.method", "\"" + a.surface + "\"")},
                                 scene.file};
                    for (std::string& c :
                         cameraAt(scene.camera, repeat, height, AO_SCENES_FOV_Y_DEG))
                        p.sets.push_back(std::move(c));
                    p.sets.insert(p.sets.end(), smaller.begin(), smaller.end());
                    pts.push_back(std::move(p));
                }
    return pts;
}

namespace {

// The wide tables: a line per scene and setting, a column per R.
void addTables(StudyResult& s, const AoCells& cells, const std::vector<std::string>& names) {
    std::vector<double> xs;  // the radii of the rows (quick runs have fewer)
    for (const auto& [scene, settings] : cells)
        for (const auto& [name, at] : settings)
            for (const auto& [r, c] : at)
                if (std::find(xs.begin(), xs.end(), r) == xs.end()) xs.push_back(r);
    std::sort(xs.begin(), xs.end());
    report::StudyTable mean{
        "mean_abs",
        "ao.mean_abs of each setting at each R (body radii), a line per scene and setting; under "
        "each scene the reference's stated standard error per pixel and the largest spread of a "
        "setting's ao.mean_abs between renders half a pixel aside.",
        {"scene", "setting"},
        {},
        {}};
    report::StudyTable falseMissed{
        "false_missed",
        "ao.false (the mean occlusion a setting adds where the truth is open) and ao.missed (the "
        "share of the truth's occlusion it leaves out; — where the truth is open) at each R "
        "(body radii).",
        {"scene", "setting", "metric"},
        {},
        {}};
    for (const double r : xs) {
        mean.columns.push_back("R " + xNumber(r));
        falseMissed.columns.push_back("R " + xNumber(r));
    }
    for (const AoScene& scene : aoScenes()) {
        const auto it = cells.find(scene.name);
        if (it == cells.end()) continue;
        report::StudyTable::Line se{{scene.name, "(truth's standard error)"}, {}};
        report::StudyTable::Line spread{{scene.name, "(largest spread)"}, {}};
        for (const std::string& name : names) {
            const auto at = it->second.find(name);
            if (at == it->second.end()) continue;
            report::StudyTable::Line e{{scene.name, name}, {}};
            report::StudyTable::Line f{{scene.name, name, "ao.false"}, {}};
            report::StudyTable::Line m{{scene.name, name, "ao.missed"}, {}};
            for (const auto& [r, c] : at->second) {
                const std::string col = "R " + xNumber(r);
                e.values[col] = c.meanAbs;
                f.values[col] = c.falseOcclusion;
                m.values[col] = c.missed;
                se.values[col] = c.standardError;
                if (std::isfinite(c.meanAbsSpread))
                    spread.values[col] = std::max(c.meanAbsSpread, spread.values[col]);
            }
            mean.lines.push_back(std::move(e));
            falseMissed.lines.push_back(std::move(f));
            falseMissed.lines.push_back(std::move(m));
        }
        mean.lines.push_back(std::move(se));
        mean.lines.push_back(std::move(spread));
    }
    s.tables.push_back(std::move(mean));
    s.tables.push_back(std::move(falseMissed));
}

// The charts: per scene the error and the false occlusion along R, a line per setting; the
// study's own, the error over the slab, where the gap closes.
void addCharts(StudyResult& s) {
    for (const AoScene& scene : aoScenes()) {
        const StudyResult one = aoSceneOnly(s, scene.name);
        if (one.rows.empty()) continue;
        report::LineChart meanChart = sceneChart(one, scene.name, "ao.mean_abs");
        if (std::string(scene.name) == "ball_over_slab")
            s.chart = meanChart;
        else
            s.figures.push_back(
                {fmt::format("mean_abs_{}", scene.name),
                 fmt::format("ao.mean_abs along R on {}, a line per setting; none dashed.",
                             scene.name),
                 std::move(meanChart)});
        report::LineChart falseChart = sceneChart(one, scene.name, "ao.false");
        falseChart.yMarks.push_back({FALSE_BOUND, "the bound of a recommended method"});
        s.figures.push_back({fmt::format("false_{}", scene.name),
                             fmt::format("ao.false along R on {}: the occlusion a setting adds "
                                         "where the truth is open; the bound {} dashed red.",
                                         scene.name, num(FALSE_BOUND)),
                             std::move(falseChart)});
    }
}

}  // namespace

// Each setting's verdict against the goal (at most FALSE_BOUND of false occlusion anywhere;
// from GAIN_FROM_R, wherever the truth is occluded, ao.mean_abs lower than none's beyond the two
// rows' spreads); each option (the filtered depth, a thickness) against its absence per method
// and scene; and which methods meet the goal at the code's defaults.
void ambientOcclusionConclude(StudyResult& s) {
    std::vector<std::string> names;  // the settings in the order of the points
    for (const AoSetting& a : aoSettings(false)) names.push_back(a.name());
    const AoCells cells = cellsOf(s);
    for (const auto& [scene, settings] : cells) {
        json open = json::array();  // the radii at which the truth has no occluded pixel
        if (const auto none = settings.find("none"); none != settings.end())
            for (const auto& [r, c] : none->second)
                if (!std::isfinite(c.missed)) open.push_back(r);
        s.facts["open"][scene] = open;
    }
    addCharts(s);
    report::StudyTable summary{
        "settings",
        fmt::format("Each setting over every scene and R: its largest ao.false and where; "
                    "against none from R {} where the truth is occluded, the points where its "
                    "ao.mean_abs is lower, tied (within the two rows' spreads half a pixel aside) "
                    "or higher; the median time of the ao pass (ms, llvmpipe); whether it meets "
                    "the goal (ao.false at most {} everywhere, lower than none at every such "
                    "point).",
                    xNumber(GAIN_FROM_R), num(FALSE_BOUND)),
        {"setting", "largest ao.false at", "meets"},
        {"largest ao.false", "lower", "tied", "higher", "ao_ms"},
        {}};
    std::map<std::string, AoVerdict> verdicts;
    std::vector<std::string> withinBound, lowerEverywhere;  // how the others miss the goal
    json recommended = json::array();
    for (const std::string& name : names) {
        const AoVerdict v = verdictOf(cells, name);
        if (name == "none" || !std::isfinite(v.worstFalse)) continue;
        verdicts[name] = v;
        summary.lines.push_back(
            {{name, atScene(v.worstFalseScene, v.worstFalseR), v.meets() ? "yes" : "no"},
             {{"largest ao.false", v.worstFalse},
              {"lower", double(v.none.lower.size())},
              {"tied", double(v.none.tie.size())},
              {"higher", double(v.none.higher.size())},
              {"ao_ms", v.aoMs}}});
        s.facts["settings"][name] = {{"worst_false", jsonOrNull(v.worstFalse)},
                                     {"worst_false_scene", v.worstFalseScene},
                                     {"worst_false_r", jsonOrNull(v.worstFalseR)},
                                     {"exceeds_bound", v.exceedsBound},
                                     {"lower", aoPointsJson(v.none.lower)},
                                     {"tie", aoPointsJson(v.none.tie)},
                                     {"higher", aoPointsJson(v.none.higher)},
                                     {"ao_ms", jsonOrNull(v.aoMs)},
                                     {"meets", v.meets()}};
        if (v.meets()) recommended.push_back(name);
        if (v.meets()) continue;
        const std::string miss = missText(name, v);
        if (!miss.empty()) (v.exceedsBound ? lowerEverywhere : withinBound).push_back(miss);
    }
    s.tables.push_back(std::move(summary));
    addTables(s, cells, names);
    std::string optionsText;
    for (const AoOption& option : aoOptions()) {
        json facts = json::object();
        const std::string text = optionText(cells, option, facts);
        if (text.empty()) continue;
        s.facts["options"][option.name] = facts;
        optionsText += (optionsText.empty() ? "" : "; ") + text;
    }
    s.facts["recommended"] = recommended;
    // The methods at the code's defaults, and whether each meets the goal there.
    std::string atDefaults;
    for (const std::string& m : AO_METHODS) {
        const std::string series = defaultSeries(m);
        const auto v = verdicts.find(series);
        const bool meets = v != verdicts.end() && v->second.meets();
        s.facts["defaults"][m] = {{"series", series}, {"meets", meets}};
        atDefaults += fmt::format("{}{} ({}) {}", atDefaults.empty() ? "" : ", ", m, series,
                                  meets ? "meets it" : "does not");
    }
    s.facts["false_bound"] = FALSE_BOUND;
    s.facts["gain_from_r"] = GAIN_FROM_R;
    // The settings' names hold commas: the lists go by semicolons.
    const auto namesOrNone = [](const std::vector<std::string>& v) {
        return v.empty() ? std::string("none") : fmt::format("{}", fmt::join(v, "; "));
    };
    s.finding = fmt::format(
        "the goal: ao.false at most {} everywhere, and from R {} wherever the truth is occluded "
        "ao.mean_abs lower than none's beyond the spread of renders half a pixel aside. Met by "
        "{}; at the defaults {}. Within the bound but not always lower: {}. Always lower but "
        "above the bound: {}. Options, better on a scene when their mean change of ao.mean_abs "
        "over its radii is below minus the mean spread: {}. Each setting's figures: "
        "settings.csv",
        num(FALSE_BOUND), xNumber(GAIN_FROM_R),
        namesOrNone(recommended.get<std::vector<std::string>>()), atDefaults,
        namesOrNone(withinBound), namesOrNone(lowerEverywhere), optionsText);
}

}  // namespace twinrender::app::study
