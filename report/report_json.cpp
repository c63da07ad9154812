#include "report/report_json.h"

#include <fmt/format.h>

#include "compare/json_number.h"
#include "core/error.h"
#include "core/image_io.h"

namespace twinrender::report {

using compare::Check;
using compare::jsonNumber;
using compare::numberFromJson;
using compare::numbersJson;
using compare::statusFromString;
using compare::toString;

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json checksArray(const std::vector<Check>& checks) {
    json a = json::array();
    for (const Check& c : checks) {
        json j = {
            {"metric", c.metric},           {"value", jsonNumber(c.value)}, {"bound", c.bound},
            {"limit", jsonNumber(c.limit)}, {"status", toString(c.status)}, {"message", c.message}};
        if (!c.where.empty()) j["where"] = c.where;
        if (c.baseline) {
            j["baseline"] = jsonNumber(*c.baseline);
            j["delta"] = jsonNumber(c.value - *c.baseline);
        }
        a.push_back(std::move(j));
    }
    return a;
}

json sequenceJson(const SequenceReport& q) {
    json frames = json::array();
    for (const SequenceFrame& f : q.frames) {
        json frame = {{"frame", f.frame}, {"metrics", numbersJson(f.metrics)}};
        if (!f.notApplicable.empty()) frame["not_applicable"] = f.notApplicable;
        frames.push_back(std::move(frame));
    }
    return {{"fps", q.fps},
            {"frames", frames},
            {"shown_frame", q.shownFrame},
            {"videos", q.videos},
            {"charts", q.charts}};
}

json timingsObject(const SceneReport& scene) {
    json t = json::object();
    for (const auto& [renderer, r] : scene.renderers) t[renderer] = numbersJson(r.timingsMs);
    return t;
}

// The error-map images by buffer (a second map of a buffer as BUFFER.NAME): path relative to
// the scene folder, label and colour range.
json errorMapsObject(const SceneReport& scene) {
    json maps = json::object();
    for (const auto& [buffer, m] : scene.errorMaps)
        maps[buffer] = {{"path", m.path},
                        {"label", m.label},
                        {"lo", jsonNumber(m.lo)},
                        {"hi", jsonNumber(m.hi)},
                        {"unit", m.unit}};
    return maps;
}

}  // namespace

// The test renderers of a run that measures several: each one's results.
json testsJson(const std::vector<TestRendererReport>& tests) {
    json a = json::array();
    for (const TestRendererReport& t : tests) {
        json j = {{"name", t.name},
                  {"metrics", numbersJson(t.metrics)},
                  {"checks", checksArray(t.checks)},
                  {"device", t.render.device},
                  {"timings_ms", numbersJson(t.render.timingsMs)},
                  {"images", t.render.images}};
        if (!t.notProvided.empty()) j["not_provided"] = t.notProvided;
        if (!t.error.empty()) j["error"] = t.error;
        a.push_back(std::move(j));
    }
    return a;
}

json metricsJson(const SceneReport& scene) {
    json j = {{"scene", scene.name},
              {"description", scene.description},
              {"status", toString(scene.status())},
              {"metrics", numbersJson(scene.metrics)},
              {"checks", checksArray(scene.checks)},
              {"timings_ms", timingsObject(scene)},
              {"error_maps", errorMapsObject(scene)}};
    if (!scene.notProvided.empty()) j["not_provided"] = scene.notProvided;
    if (!scene.notApplicable.empty()) j["not_applicable"] = scene.notApplicable;
    if (!scene.error.empty()) j["error"] = scene.error;
    if (scene.sequence) j["sequence"] = sequenceJson(*scene.sequence);
    if (!scene.tests.empty()) j["tests"] = testsJson(scene.tests);
    return j;
}

json summaryJson(const RunReport& run) {
    json scenes = json::array();
    for (const SceneReport& s : run.scenes) {
        json j = {{"name", s.name},
                  {"status", toString(s.status())},
                  {"metrics", numbersJson(s.metrics)},
                  {"timings_ms", timingsObject(s)},
                  {"checks", checksArray(s.checks)},
                  {"settings", s.settings}};
        if (!s.error.empty()) j["error"] = s.error;
        scenes.push_back(std::move(j));
    }
    return {{"status", toString(run.status())},
            {"scenes", scenes},
            {"thresholds", run.thresholdsFile},
            {"baseline", run.baselineFile},
            {"created", run.createdAt}};
}

void writeMetricsJson(const SceneReport& scene, const fs::path& file) {
    core::writeTextFile(file, metricsJson(scene).dump(2) + "\n");
}

void writeSummaryJson(const RunReport& run, const fs::path& file) {
    core::writeTextFile(file, summaryJson(run).dump(2) + "\n");
}

json sceneReportJson(const SceneReport& scene) {
    json j = metricsJson(scene);
    j["baseline"] = numbersJson(scene.baseline);
    json renderers = json::object();
    for (const auto& [name, r] : scene.renderers) {
        renderers[name] = {{"timings_ms", numbersJson(r.timingsMs)},
                           {"device", r.device},
                           {"counters", numbersJson(r.counters)},
                           {"images", r.images}};
    }
    j["renderers"] = renderers;
    j["settings"] = scene.settings;
    return j;
}

SceneReport sceneReportFromJson(const json& j, const std::string& source) {
    auto bad = [&](const std::string& what) {
        return core::InputError(
            fmt::format("{}: {} (expected a scene report as twinrender writes it)", source, what));
    };
    auto number = [&](const json& v, const std::string& where) {
        const auto n = numberFromJson(v);
        if (!n) throw bad(where + " is not a number");
        return *n;
    };
    auto numbers = [&](const json& obj, const std::string& where) {
        std::map<std::string, double> m;
        if (obj.is_null()) return m;
        if (!obj.is_object()) throw bad(where + " is not an object");
        for (const auto& [k, v] : obj.items()) m[k] = number(v, where + "." + k);
        return m;
    };
    try {
        SceneReport s;
        s.name = j.at("scene").get<std::string>();
        s.description = j.value("description", "");
        s.metrics = numbers(j.at("metrics"), "metrics");
        s.baseline = numbers(j.value("baseline", json()), "baseline");
        s.notProvided = j.value("not_provided", std::vector<std::string>{});
        s.notApplicable = j.value("not_applicable", std::map<std::string, std::string>{});
        auto checks = [&](const json& a) {
            std::vector<Check> out;
            for (const json& c : a) {
                Check k;
                k.metric = c.at("metric").get<std::string>();
                k.value = number(c.at("value"), "checks[].value");
                k.bound = c.at("bound").get<std::string>();
                k.limit = number(c.at("limit"), "checks[].limit");
                const auto st = statusFromString(c.at("status").get<std::string>());
                if (!st) throw bad("checks[].status is not pass, warn or fail");
                k.status = *st;
                k.message = c.value("message", "");
                k.where = c.value("where", "");
                if (c.contains("baseline"))
                    k.baseline = number(c.at("baseline"), "checks[].baseline");
                out.push_back(std::move(k));
            }
            return out;
        };
        s.checks = checks(j.at("checks"));
        for (const json& t : j.value("tests", json::array())) {
            TestRendererReport r;
            r.name = t.at("name").get<std::string>();
            r.metrics = numbers(t.at("metrics"), "tests[].metrics");
            r.notProvided = t.value("not_provided", std::vector<std::string>{});
            r.checks = checks(t.at("checks"));
            r.error = t.value("error", "");
            r.render.device = t.value("device", "");
            r.render.timingsMs = numbers(t.value("timings_ms", json()), "tests[].timings_ms");
            r.render.images = t.value("images", std::map<std::string, std::string>{});
            s.tests.push_back(std::move(r));
        }
        const json renderers = j.value("renderers", json::object());
        for (const auto& [name, r] : renderers.items()) {
            RendererReport rr;
            rr.timingsMs =
                numbers(r.value("timings_ms", json()), "renderers." + name + ".timings_ms");
            rr.device = r.value("device", "");
            rr.counters = numbers(r.value("counters", json()), "renderers." + name + ".counters");
            rr.images = r.value("images", std::map<std::string, std::string>{});
            s.renderers[name] = std::move(rr);
        }
        const json maps = j.value("error_maps", json::object());
        for (const auto& [buffer, m] : maps.items())
            s.errorMaps[buffer] = {m.at("path").get<std::string>(), m.value("label", ""),
                                   number(m.at("lo"), "error_maps.lo"),
                                   number(m.at("hi"), "error_maps.hi"), m.value("unit", "")};
        s.settings = j.value("settings", json());
        s.error = j.value("error", "");
        if (j.contains("sequence")) {
            const json& q = j.at("sequence");
            SequenceReport r;
            r.fps = number(q.at("fps"), "sequence.fps");
            for (const json& f : q.at("frames"))
                r.frames.push_back(
                    {.frame = f.at("frame").get<std::int64_t>(),
                     .metrics = numbers(f.at("metrics"), "sequence.frames[].metrics"),
                     .notApplicable =
                         f.value("not_applicable", std::map<std::string, std::string>{})});
            r.shownFrame = q.value("shown_frame", std::int64_t{0});
            r.videos = q.value("videos", std::map<std::string, std::string>{});
            r.charts = q.value("charts", std::map<std::string, std::string>{});
            s.sequence = std::move(r);
        }
        return s;
    } catch (const json::exception& e) {
        throw bad(e.what());
    }
}

}  // namespace twinrender::report
