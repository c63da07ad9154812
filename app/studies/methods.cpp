// The methods study (docs/studies.md, docs/methods.md): every surface method, its cost and its
// error.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "app/studies/common.h"
#include "app/studies/study_list.h"
#include "core/install_layout.h"
#include "core/stage_table.h"
#include "realtime/settings.h"
#include "report/study_summary.h"

namespace twinrender::app::study {

namespace {

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

}  // namespace

// On the default scenes, x is the method's parameter (0 for none); along particle size the
// pixels per particle (NaN here: particlePixels computes it), along view angle the degrees.
// Where the conclusion compares normal errors (each method at its default on the default
// scenes, every point along size and angle) a point is rendered again with the camera turned
// half a pixel: the noise its ties rest on.
std::vector<StudyPoint> methodsPoints(bool quick) {
    std::vector<StudyPoint> pts;
    for (const SuiteScene& scene : suiteScenes(quick)) {
        std::vector<StudyPoint> repeats;
        for (const std::string& shape : SHAPES)
            for (const MethodSweep& m : methodSweeps())
                for (double v : sweepValues(m, quick)) {
                    pts.push_back(
                        methodPoint(m, v, shape, "../" + scene.name + ".toml", scene.sets));
                    // Each method at its default again with the camera turned half a pixel (the
                    // noise its comparison with none rests on), timed with its scene's points.
                    if (v == m.defaultValue || !m.key) repeats.push_back(repeatOf(pts.back()));
                }
        pts.insert(pts.end(), repeats.begin(), repeats.end());
    }
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
                pts.push_back(repeatOf(pts.back()));
            }
    for (const std::string& shape : SHAPES)
        for (const MethodSweep& m : methodSweeps())
            for (double deg : angles) {
                StudyPoint p =
                    methodPoint(m, m.defaultValue, shape, ANGLE_SCENE + ".toml", angleCamera(deg));
                p.x = deg;
                pts.push_back(std::move(p));
                pts.push_back(repeatOf(pts.back()));
            }
    // Quick: a coarse shadow map, the largest stage of these small frames on llvmpipe.
    if (quick)
        for (StudyPoint& p : pts) p.sets.push_back("realtime.shadow_map.resolution=256");
    return pts;
}

namespace {

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

const std::string NORMAL = "normal.mean_deg";

// Per series in order of first appearance, its x -> row over some rows (one scene's).
using RowsByX = std::vector<std::pair<std::string, std::map<double, const StudyRow*>>>;
RowsByX rowsBySeries(const std::vector<const StudyRow*>& rows) {
    RowsByX out;
    for (const StudyRow* r : rows) {
        if (!r->error.empty()) continue;
        auto it = std::find_if(out.begin(), out.end(),
                               [&](const auto& p) { return p.first == r->series; });
        if (it == out.end()) it = out.insert(out.end(), {r->series, {}});
        it->second[r->x] = r;
    }
    return out;
}
const std::map<double, const StudyRow*>* rowsOf(const RowsByX& all, const std::string& series) {
    for (const auto& [name, rows] : all)
        if (name == series) return &rows;
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

// Along particle size: where each method helps (its normal error below its control's beyond
// the two rows' spreads, their difference from a render with the camera turned half a pixel)
// and where it raises the error (above it likewise).
std::string sizeFinding(const StudyResult& s, const std::vector<const StudyRow*>& rows,
                        json& facts) {
    const auto all = rowsBySeries(rows);
    std::string out;
    for (const auto& [series, byX] : all) {
        const auto* control = rowsOf(all, controlOf(series));
        if (!control) continue;
        std::vector<double> helps, raises;
        json gains = json::object(), against = json::object();
        for (const auto& [x, r] : byX) {
            const auto c = control->find(x);
            if (c == control->end()) continue;
            const std::string key = fmt::format("{:.4g}", x);
            gains[key] = jsonOrNull(1.0 - metricOf(*r, NORMAL) / metricOf(*c->second, NORMAL));
            const Order o = orderOf(s, *r, *c->second, NORMAL);
            against[key] = orderName(o);
            if (o == Order::Lower) helps.push_back(x);
            if (o == Order::Higher) raises.push_back(x);
        }
        auto list = [](const std::vector<double>& xs) {
            std::string t;
            for (double x : xs) t += (t.empty() ? "" : ", ") + num(x);
            return t;
        };
        // Contiguous: every size between the smallest and the largest that helps helps too.
        bool contiguous = true;
        for (const auto& [x, r] : byX)
            if (!helps.empty() && x > helps.front() && x < helps.back() &&
                std::find(helps.begin(), helps.end(), x) == helps.end())
                contiguous = false;
        json& f = facts[series];
        f["control"] = controlOf(series);
        f["gain"] = gains;
        f["against_control"] = against;
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

// "lower", "a tie", "higher": an order as a finding's brackets write it.
std::string orderWords(Order o) {
    return o == Order::Tie ? "a tie" : orderName(o);
}

// Along view angle, each beyond the two rows' spreads: from which angle each method raises the
// error above its control's for good, and how its error at the largest angle stands to its
// face-on one.
std::string angleFinding(const StudyResult& s, const std::vector<const StudyRow*>& rows,
                         json& facts) {
    const auto all = rowsBySeries(rows);
    std::string raised, growth;
    for (const auto& [series, byX] : all) {
        const auto* control = rowsOf(all, controlOf(series));
        if (!control || byX.empty()) continue;
        double from = NAN;
        for (auto it = byX.rbegin(); it != byX.rend(); ++it) {
            const auto c = control->find(it->first);
            if (c == control->end() || orderOf(s, *it->second, *c->second, NORMAL) != Order::Higher)
                break;
            from = it->first;
        }
        const StudyRow &faceOn = *byX.begin()->second, &last = *byX.rbegin()->second;
        const Order trend = orderOf(s, last, faceOn, NORMAL);
        const std::string name = methodName(series);
        json& f = facts[series];
        f["control"] = controlOf(series);
        f["raises_from_deg"] = jsonOrNull(from);
        f["face_on_deg"] = jsonOrNull(metricOf(faceOn, NORMAL));
        f["last_angle"] = last.x;
        f["last_deg"] = jsonOrNull(metricOf(last, NORMAL));
        f["toward_grazing"] = orderName(trend);
        if (std::isfinite(from))
            raised += fmt::format("{}{} from {}°", raised.empty() ? "" : ", ", name, num(from));
        growth += fmt::format("{}{} {}° → {}° ({})", growth.empty() ? "" : ", ", name,
                              num(metricOf(faceOn, NORMAL)), num(metricOf(last, NORMAL)),
                              orderWords(trend));
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
           fmt::format("; face-on → {}° (the error at {}° against face-on's): {}", num(last),
                       num(last), growth);
}

report::LineChart alongChart(const std::vector<const StudyRow*>& rows, const std::string& title,
                             const std::string& xLabel, bool xLog) {
    report::LineChart c;
    c.title = title;
    c.xLabel = xLabel;
    c.yLabel = "normal.mean_deg (°)";
    c.xScale = xLog ? report::AxisScale::Log : report::AxisScale::Linear;
    for (const auto& [series, byX] : rowsBySeries(rows)) {
        report::LineSeries line{series, {}, false};
        for (const auto& [x, r] : byX) line.points.push_back({x, metricOf(*r, NORMAL), ""});
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
    for (const auto& [series, byX] : rowsBySeries(rows)) {
        const auto [method, shape] = methodAndShape(series);
        report::StudyTable::Line line{{method, shape}, {}};
        for (const auto& [x, r] : byX) line.values[column(x)] = metricOf(*r, NORMAL);
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

// A setting's median normal error and its noise: the difference from the median of its repeats
// (the same setting on the same scenes with the camera turned half a pixel); NaN where it has
// none.
Measured medianNormal(const report::SettingMedians& st,
                      const std::vector<report::SettingMedians>& repeats) {
    Measured m{.name = st.series, .value = normalOf(st), .spread = NAN};
    for (const auto& r : repeats)
        if (r.series == st.series + REPEAT && r.x == st.x) {
            const double d = std::abs(normalOf(r) - m.value);
            m.spread = std::isfinite(d) ? d : NAN;
        }
    return m;
}

// Each method at its default against none of its shape: its error and time over none's, and a
// depth filter's error over its control's; lower, a tie or higher beyond the two medians'
// spreads.
std::string againstNoneFinding(const std::vector<report::SettingMedians>& settings,
                               const std::vector<report::SettingMedians>& repeats, json& facts) {
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
        const Measured self = medianNormal(st, repeats);
        const double e = normalOf(st) / normalOf(*n), t = timeOf(st) / timeOf(*n);
        const Order toNone = orderWithin(self, medianNormal(*n, repeats));
        facts[label] = {{"normal_ratio", jsonOrNull(e)},
                        {"time_ratio", jsonOrNull(t)},
                        {"normal_spread", jsonOrNull(self.spread)},
                        {"against_none", orderName(toNone)}};
        std::string versus =
            fmt::format("{}x {}: {}", num(e), settingLabel(n->series, n->x), orderWords(toNone));
        if (const auto* c = find(controlOf(st.series)); c && c != n) {
            const Order toControl = orderWithin(self, medianNormal(*c, repeats));
            facts[label]["control_normal_ratio"] = jsonOrNull(normalOf(st) / normalOf(*c));
            facts[label]["against_control"] = orderName(toControl);
            versus += fmt::format(", {}x {}: {}", num(normalOf(st) / normalOf(*c)),
                                  settingLabel(c->series, c->x), orderWords(toControl));
        }
        against += fmt::format("{}{} {}° ({}) at {}x the time", against.empty() ? "" : ", ", label,
                               num(normalOf(st)), versus, num(t));
    }
    return fmt::format(
        "at their defaults against none ({}; lower, a tie or higher beyond the two medians' "
        "noise, their difference from the medians of renders with the camera turned half a "
        "pixel): {}",
        none, against);
}

// The chart of the default scenes: a point per setting, a colour per method and shape; and
// the settings as facts.
report::ScatterChart frontChart(const std::vector<report::SettingMedians>& settings,
                                const std::vector<report::SettingMedians>& repeats,
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
                         {"normal_spread", jsonOrNull(medianNormal(st, repeats).spread)},
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

}  // namespace

void methodsConclude(StudyResult& s) {
    // The rows of each part, and the default scenes' repeats apart (along size and angle the
    // repeats are found by spreadAt).
    std::vector<const StudyRow*> suite, suiteRepeats, size, angle;
    for (const StudyRow& r : s.rows)
        (r.scene == SIZE_SCENE    ? size
         : r.scene == ANGLE_SCENE ? angle
         : isRepeat(r)            ? suiteRepeats
                                  : suite)
            .push_back(&r);
    std::erase_if(size, [](const StudyRow* r) { return isRepeat(*r); });
    std::erase_if(angle, [](const StudyRow* r) { return isRepeat(*r); });
    std::vector<std::string> scenes;
    for (const StudyRow* r : suite)
        if (std::find(scenes.begin(), scenes.end(), r->scene) == scenes.end())
            scenes.push_back(r->scene);
    const auto settings = report::mediansOverScenes(suite);
    const auto repeats = report::mediansOverScenes(suiteRepeats);
    const auto front = report::settingsFront(settings, "normal.mean_deg");
    s.facts["scenes"] = scenes;
    s.facts["shapes"] = SHAPES;
    s.facts["aggregate"] = "median over the default scenes";
    s.scatter = frontChart(settings, repeats, front, scenes.size(), s.facts["settings"]);
    if (settings.empty()) {
        s.finding = "no render of the default scenes to compare";
        return;
    }
    s.finding = fmt::format(
        "on {} default scenes (medians), the Pareto front of frame time against normal error is "
        "{}; {}",
        scenes.size(), frontFinding(settings, front, s.facts["front"]),
        againstNoneFinding(settings, repeats, s.facts["against_none"]));
    if (!size.empty())
        s.finding +=
            "; along particle size, where each method's normal error is below its control's "
            "(none for ssss and depth_normals, depth_normals for the depth filters) beyond the "
            "two rows' noise, their difference from a render with the camera turned half a "
            "pixel: " +
            sizeFinding(s, size, s.facts["particle_size"]);
    if (!angle.empty())
        s.finding += "; along view angle, beyond the same noise, " +
                     angleFinding(s, angle, s.facts["view_angle"]);

    suiteTables(s, settings, front, suite, scenes);
    addAlong(s, size, SIZE_SCENE, "particle size", "particle diameter on screen (px)", true,
             [](double x) { return fmt::format("{:.3g} px", x); });
    addAlong(s, angle, ANGLE_SCENE, "view angle", "view angle from the surface normal (degrees)",
             false, [](double x) { return fmt::format("{:g}°", x); });
}

}  // namespace twinrender::app::study
