#include "compare/baseline.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <set>

#include "compare/json_number.h"
#include "compare/settings_keys.h"
#include "core/error.h"
#include "core/folder_name.h"
#include "core/image_io.h"

namespace twinrender::compare {

namespace fs = std::filesystem;
using nlohmann::json;

BaselinePolicy defaultPolicy(std::string_view metric) {
    const MetricInfo* m = findMetric(metric);
    if (!m) return {};
    // Times vary with the machine and its load by tens of percent: recorded and shown with
    // their deltas, checked only where a baseline file turns them on.
    if (m->machineDependent) return {m->better, m->origin, 0.25, m->noise, false};
    return {m->better, m->origin, 0.02, m->noise, true};
}

double allowedWorsening(const BaselinePolicy& policy, double baseline) {
    if (!std::isfinite(baseline)) return policy.absolute;
    return std::max(policy.relative * std::abs(baseline - policy.origin), policy.absolute);
}

BaselinePolicy Baseline::policy(const std::string& metric) const {
    auto it = tolerances.find(metric);
    return it != tolerances.end() ? it->second : defaultPolicy(metric);
}

const MetricValues* Baseline::metrics(const std::string& scene) const {
    auto it = scenes.find(scene);
    return it != scenes.end() ? &it->second.metrics : nullptr;
}

// ---- bless -----------------------------------------------------------------------------

Baseline bless(const json& summary, const std::string& source) {
    const std::string where = source.empty() ? std::string("summary") : source;
    auto bad = [&](const std::string& path, const std::string& what) {
        return core::InputError(
            fmt::format("{}: '{}' {}; is this a twinrender summary.json?", where, path, what));
    };
    if (!summary.is_object() || !summary.contains("scenes") || !summary["scenes"].is_array())
        throw bad("scenes", "is missing or not an array");
    Baseline b;
    b.blessedFrom = source;
    std::size_t i = 0;
    for (const json& s : summary["scenes"]) {
        const std::string at = fmt::format("scenes[{}]", i++);
        if (!s.is_object() || !s.contains("name") || !s["name"].is_string())
            throw bad(at + ".name", "is missing or not a string");
        const std::string name = s["name"].get<std::string>();
        if (const std::string problem = core::folderNameProblem(name); !problem.empty())
            throw bad(at + ".name", fmt::format("is not a scene name: it {}", problem));
        if (b.scenes.count(name)) throw bad(at + ".name", fmt::format("repeats scene '{}'", name));
        if (!s.contains("metrics") || s["metrics"].is_null()) continue;  // scene did not render
        if (!s["metrics"].is_object()) throw bad(at + ".metrics", "is not an object");
        BaselineScene scene;
        for (const auto& [key, v] : s["metrics"].items()) {
            auto value = numberFromJson(v);
            if (!value && !v.is_null()) throw bad(at + ".metrics." + key, "is not a number");
            if (!value || std::isnan(*value)) continue;  // not computable: nothing to hold to
            scene.metrics[key] = *value;
            if (!b.tolerances.count(key)) b.tolerances[key] = defaultPolicy(key);
        }
        if (s.contains("settings")) scene.settings = s["settings"];
        if (!scene.metrics.empty()) b.scenes[name] = std::move(scene);
    }
    return b;
}

namespace {

json readJsonFile(const fs::path& file, const std::string& what) {
    std::ifstream in(file);
    if (!in.is_open())
        throw core::InputError(fmt::format("{}: cannot read the {}", file.string(), what));
    try {
        return json::parse(in);
    } catch (const json::exception& e) {
        // Not JSON, or a number beyond double (out_of_range 406: "99999999e999").
        throw core::InputError(
            fmt::format("{}: the {} is not valid JSON: {}", file.string(), what, e.what()));
    }
}

}  // namespace

Baseline blessRunDir(const fs::path& runDir) {
    const fs::path summary = runDir / "summary.json";
    std::error_code ec;
    if (!fs::is_regular_file(summary, ec))
        throw core::InputError(
            fmt::format("{}: no summary.json; bless the folder a "
                        "'twinrender run --out DIR' wrote",
                        runDir.string()));
    return bless(readJsonFile(summary, "run summary"), summary.string());
}

// ---- file format -----------------------------------------------------------------------

json toJson(const Baseline& baseline) {
    json j = json::object();
    j["format"] = "twinrender-baseline";
    j["version"] = 1;
    j["blessed_from"] = baseline.blessedFrom;
    json tol = json::object();
    for (const auto& [metric, p] : baseline.tolerances)
        tol[metric] = {{"better", toString(p.better)},
                       {"origin", p.origin},
                       {"relative", p.relative},
                       {"absolute", p.absolute},
                       {"checked", p.checked}};
    j["tolerances"] = tol;
    json scenes = json::object();
    for (const auto& [name, s] : baseline.scenes) {
        json m = json::object();
        for (const auto& [k, v] : s.metrics) m[k] = jsonNumber(v);
        scenes[name] = {{"metrics", m}, {"settings", s.settings}};
    }
    j["scenes"] = scenes;
    return j;
}

Baseline parseBaseline(const json& j, const std::string& file) {
    auto bad = [&](const std::string& key, const std::string& what) {
        return core::InputError(fmt::format("{}: key '{}' {}", file, key, what));
    };
    // "format" of any type (a duplicated key keeps the last): compared, never converted.
    if (!j.is_object() || !j.contains("format") || j["format"] != "twinrender-baseline")
        throw core::InputError(fmt::format(
            "{}: not a twinrender baseline (no \"format\": \"twinrender-baseline\"); make one "
            "with 'twinrender bless RUN_DIR'",
            file));
    if (!j.contains("version") || !j["version"].is_number_integer() || j["version"].get<int>() != 1)
        throw bad("version", "must be 1; this twinrender reads baseline version 1 only");
    for (const auto& [k, v] : j.items())
        if (k != "format" && k != "version" && k != "blessed_from" && k != "tolerances" &&
            k != "scenes")
            throw bad(k,
                      "is unknown; a baseline has format, version, blessed_from, tolerances "
                      "and scenes");
    Baseline b;
    b.file = file;
    if (j.contains("blessed_from") && j["blessed_from"].is_string())
        b.blessedFrom = j["blessed_from"].get<std::string>();
    if (j.contains("tolerances")) {
        if (!j["tolerances"].is_object()) throw bad("tolerances", "must be an object");
        for (const auto& [metric, t] : j["tolerances"].items()) {
            const std::string at = "tolerances." + metric;
            if (!t.is_object()) throw bad(at, "must be an object");
            BaselinePolicy p = defaultPolicy(metric);
            for (const auto& [k, v] : t.items()) {
                const std::string key = at + "." + k;
                if (k == "better") {
                    const std::string s = v.is_string() ? v.get<std::string>() : "";
                    if (s == "higher")
                        p.better = Better::Higher;
                    else if (s == "lower")
                        p.better = Better::Lower;
                    else if (s == "closer")
                        p.better = Better::Closer;
                    else
                        throw bad(key, "must be \"higher\", \"lower\" or \"closer\"");
                } else if (k == "checked") {
                    if (!v.is_boolean()) throw bad(key, "must be true or false");
                    p.checked = v.get<bool>();
                } else if (k == "origin" || k == "relative" || k == "absolute") {
                    if (!v.is_number() || !std::isfinite(v.get<double>()))
                        throw bad(key, "must be a finite number");
                    const double x = v.get<double>();
                    if (k != "origin" && x < 0.0) throw bad(key, "must be >= 0");
                    (k == "origin" ? p.origin : k == "relative" ? p.relative : p.absolute) = x;
                } else {
                    throw bad(key,
                              "is unknown; a tolerance has better, origin, relative, "
                              "absolute and checked");
                }
            }
            b.tolerances[metric] = p;
        }
    }
    if (j.contains("scenes")) {
        if (!j["scenes"].is_object()) throw bad("scenes", "must be an object");
        for (const auto& [name, s] : j["scenes"].items()) {
            // A scene's name names a folder (core/folder_name.h): a baseline names no other.
            if (const std::string problem = core::folderNameProblem(name); !problem.empty())
                throw bad("scenes." + core::printable(name),
                          fmt::format("is not a scene name: it {}", problem));
            const std::string at = "scenes." + name;
            if (!s.is_object() || !s.contains("metrics") || !s["metrics"].is_object())
                throw bad(at + ".metrics", "is missing or not an object");
            BaselineScene scene;
            for (const auto& [k, v] : s["metrics"].items()) {
                auto value = numberFromJson(v);
                if (!value || std::isnan(*value))
                    throw bad(at + ".metrics." + k, "must be a number");
                scene.metrics[k] = *value;
            }
            if (s.contains("settings")) scene.settings = s["settings"];
            b.scenes[name] = std::move(scene);
        }
    }
    return b;
}

Baseline readBaseline(const fs::path& file) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
        throw core::InputError(
            fmt::format("{}: baseline file not found; make one with "
                        "'twinrender bless RUN_DIR --out FILE'",
                        file.string()));
    return parseBaseline(readJsonFile(file, "baseline"), file.string());
}

void writeBaseline(const Baseline& baseline, const fs::path& file) {
    core::writeTextFile(file, toJson(baseline).dump(2) + "\n");
}

// ---- comparison ------------------------------------------------------------------------

namespace {

// Setting (its dotted key) -> value as JSON text.
std::map<std::string, std::string> settingValues(const json& settings) {
    std::map<std::string, std::string> out;
    if (settings.is_null()) return out;
    for (const auto& [key, value] : flattenSettings(settings))
        out[key.empty() ? std::string("(settings)") : key] = value.dump();
    return out;
}

std::string signedValue(double v) {
    return fmt::format("{}{}", v > 0 || (v == 0 && !std::signbit(v)) ? "+" : "", formatValue(v));
}

}  // namespace

std::string changeText(double value, double baseline) {
    const double d = value - baseline;
    std::string text = fmt::format("{}{}", d > 0 ? "+" : "", formatValue(d));
    if (baseline != 0.0 && std::isfinite(d) && std::isfinite(baseline) && d != 0.0)
        text += fmt::format(" ({}{:.1f} %)", d > 0 ? "+" : "", 100.0 * d / std::abs(baseline));
    return text;
}

std::vector<std::string> settingsChanges(const json& before, const json& after) {
    const std::map<std::string, std::string> a = settingValues(before), b = settingValues(after);
    std::vector<std::string> out;
    for (const auto& [k, v] : a) {
        auto it = b.find(k);
        if (it == b.end())
            out.push_back(fmt::format("{}: removed (was {})", k, v));
        else if (it->second != v)
            out.push_back(fmt::format("{}: {} -> {}", k, v, it->second));
    }
    for (const auto& [k, v] : b)
        if (!a.count(k)) out.push_back(fmt::format("{}: added ({})", k, v));
    return out;
}

std::vector<Check> compareToBaseline(const std::string& scene, const MetricValues& metrics,
                                     const Baseline& baseline, const json* settings) {
    std::vector<Check> checks;
    auto sit = baseline.scenes.find(scene);
    if (sit == baseline.scenes.end()) return checks;
    const BaselineScene& blessed = sit->second;
    const std::string where = baseline.file.empty() ? std::string("baseline") : baseline.file;

    std::string changed;
    if (settings) {
        const auto lines = settingsChanges(blessed.settings, *settings);
        if (lines.empty() && !blessed.settings.is_null()) {
            changed = "; the scene's settings are the same as at the baseline";
        } else if (!lines.empty()) {
            changed = "; settings changed since the baseline: ";
            const std::size_t shown = std::min<std::size_t>(lines.size(), 8);
            for (std::size_t i = 0; i < shown; ++i) changed += (i ? ", " : "") + lines[i];
            if (lines.size() > shown) changed += fmt::format(" and {} more", lines.size() - shown);
        }
    }

    for (const auto& [metric, base] : blessed.metrics) {
        const BaselinePolicy p = baseline.policy(metric);
        if (!p.checked) continue;
        const double allowed = allowedWorsening(p, base);
        Check c;
        c.metric = metric;
        c.bound = "baseline";
        c.baseline = base;
        c.where = where;
        switch (p.better) {
            case Better::Higher:
                c.limit = base - allowed;
                break;
            case Better::Lower:
                c.limit = base + allowed;
                break;
            case Better::Closer:
                c.limit = p.origin;
                break;  // refined below, by the value's side
        }
        auto it = metrics.find(metric);
        if (it == metrics.end()) {
            c.value = std::nan("");
            c.status = Status::Fail;
            c.message = fmt::format("{} was {} at the baseline but was not computed in this run",
                                    metric, formatValue(base));
            checks.push_back(std::move(c));
            continue;
        }
        const double v = it->second;
        c.value = v;
        if (std::isnan(v)) {
            c.status = Status::Fail;
            c.message = fmt::format("{} is not computable (NaN); it was {} at the baseline", metric,
                                    formatValue(base));
            checks.push_back(std::move(c));
            continue;
        }
        double worsening = 0.0;  // > 0: worse
        switch (p.better) {
            case Better::Higher:
                worsening = v == base ? 0.0 : base - v;
                break;
            case Better::Lower:
                worsening = v == base ? 0.0 : v - base;
                break;
            case Better::Closer: {
                worsening = std::abs(v - p.origin) - std::abs(base - p.origin);
                const double reach = std::abs(base - p.origin) + allowed;
                c.limit = v >= p.origin ? p.origin + reach : p.origin - reach;
                break;
            }
        }
        const double delta = v - base;
        const std::string deltaText =
            base != 0.0 && std::isfinite(base) && std::isfinite(delta)
                ? fmt::format("delta {}, {}{:.1f} %", signedValue(delta), delta >= 0 ? "+" : "",
                              100.0 * delta / std::abs(base))
                : fmt::format("delta {}", signedValue(delta));
        const std::string change =
            fmt::format("{} -> {} ({})", formatValue(base), formatValue(v), deltaText);
        if (worsening > allowed) {
            c.status = Status::Fail;
            const std::string rule =
                std::isfinite(base) && p.relative > 0.0
                    ? fmt::format("{} % of {}, at least {}", formatValue(100.0 * p.relative),
                                  p.origin == 0.0 ? formatValue(std::abs(base))
                                                  : fmt::format("|{} - {}|", formatValue(base),
                                                                formatValue(p.origin)),
                                  formatValue(p.absolute))
                    : fmt::format("absolute {}", formatValue(p.absolute));
            c.message = fmt::format(
                "{} got worse than the baseline: {}; the tolerance allows {} "
                "({}){}",
                metric, change, formatValue(allowed), rule, changed);
        } else {
            c.status = Status::Pass;
            c.message = fmt::format("{} {} the baseline: {}", metric,
                                    worsening < 0.0    ? "is better than"
                                    : worsening == 0.0 ? "equals"
                                                       : "is within the tolerance of",
                                    change);
        }
        checks.push_back(std::move(c));
    }
    return checks;
}

}  // namespace twinrender::compare
