#include "compare/thresholds.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "compare/metric_table.h"
#include "core/error.h"

namespace twinrender::compare {

namespace fs = std::filesystem;

std::string_view toString(Status status) {
    switch (status) {
        case Status::Pass:
            return "pass";
        case Status::Warn:
            return "warn";
        case Status::Fail:
            return "fail";
    }
    return "fail";
}

std::optional<Status> statusFromString(std::string_view text) {
    for (Status s : {Status::Pass, Status::Warn, Status::Fail})
        if (toString(s) == text) return s;
    return std::nullopt;
}

Status worst(Status a, Status b) {
    return static_cast<int>(a) >= static_cast<int>(b) ? a : b;
}

Status overallStatus(const std::vector<Check>& checks) {
    Status s = Status::Pass;
    for (const Check& c : checks) s = worst(s, c.status);
    return s;
}

const std::vector<std::string>& boundNames() {
    static const std::vector<std::string> names = {"max", "min", "warn_max", "warn_min"};
    return names;
}

std::string formatValue(double value) {
    if (std::isnan(value)) return "NaN";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    const double a = std::abs(value);
    if (a >= 1e4 && a < 1e9) return fmt::format("{:.0f}", value);
    return fmt::format("{:.4g}", value);
}

std::string exactValue(double value) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    return fmt::format("{}", value);
}

namespace {

const char* BOUND_HINT =
    "write \"METRIC\" = { max = ..., warn_max = ... } with the bounds max, min, warn_max, warn_min";

std::optional<Limit>& slot(MetricBounds& b, const std::string& bound) {
    if (bound == "max") return b.max;
    if (bound == "min") return b.min;
    if (bound == "warn_max") return b.warnMax;
    return b.warnMin;
}

const std::optional<Limit>& slot(const MetricBounds& b, const std::string& bound) {
    return slot(const_cast<MetricBounds&>(b), bound);
}

bool isBoundName(const std::string& s) {
    for (const auto& b : boundNames())
        if (b == s) return true;
    return false;
}

// Adds one "METRIC.BOUND" = value; `where` and `shownKey` are for messages.
void addBound(Bounds& out, const std::string& key, std::optional<double> value,
              const std::string& where, const std::string& shownKey) {
    const auto dot = key.rfind('.');
    if (dot == std::string::npos || dot == 0)
        throw core::InputError(fmt::format("{}: key '{}' is a bound without a metric; {}", where,
                                           shownKey, BOUND_HINT));
    const std::string metric = key.substr(0, dot);
    const std::string bound = key.substr(dot + 1);
    if (!isBoundName(bound))
        throw core::InputError(fmt::format("{}: key '{}': unknown bound '{}' for metric '{}'; {}",
                                           where, shownKey, bound, metric, BOUND_HINT));
    if (!findMetric(metric))
        throw core::InputError(fmt::format("{}: key '{}': unknown metric '{}'; the metrics are {}",
                                           where, shownKey, metric, metricNames()));
    if (!value)
        throw core::InputError(
            fmt::format("{}: key '{}': the bound must be a number", where, shownKey));
    if (!std::isfinite(*value))
        throw core::InputError(
            fmt::format("{}: key '{}': the bound must be a finite number, got {}", where, shownKey,
                        formatValue(*value)));
    slot(out[metric], bound) = Limit{*value, where};
}

// A warn bound beyond its fail bound can never warn; that is a typo, not a policy.
void checkConsistent(const Bounds& bounds) {
    for (const auto& [metric, b] : bounds) {
        if (b.max && b.warnMax && b.warnMax->value > b.max->value)
            throw core::InputError(fmt::format(
                "{}: '{}' has warn_max {} above its max {}; a warning bound must be stricter "
                "than the failing one",
                b.warnMax->where, metric, formatValue(b.warnMax->value),
                formatValue(b.max->value)));
        if (b.min && b.warnMin && b.warnMin->value < b.min->value)
            throw core::InputError(fmt::format(
                "{}: '{}' has warn_min {} below its min {}; a warning bound must be stricter "
                "than the failing one",
                b.warnMin->where, metric, formatValue(b.warnMin->value),
                formatValue(b.min->value)));
    }
}

std::string whereOf(const std::string& file, const toml::node& node) {
    const auto& src = node.source();
    if (src.begin.line == 0) return file;
    return fmt::format("{}:{}:{}", file, src.begin.line, src.begin.column);
}

// One key of a thresholds table: a table descends, a value is the bound "METRIC.BOUND".
void walkNode(const std::string& key, const toml::node& node, const std::string& shownPrefix,
              const std::string& file, Bounds& out) {
    const std::string shown = shownPrefix.empty() ? key : shownPrefix + "." + key;
    if (const auto* t = node.as_table()) {
        for (const auto& [k, child] : *t)
            walkNode(key + "." + std::string(k.str()), child, shownPrefix, file, out);
        return;
    }
    std::optional<double> value;
    if (auto i = node.value_exact<std::int64_t>())
        value = static_cast<double>(*i);
    else if (auto d = node.value_exact<double>())
        value = *d;
    addBound(out, key, value, whereOf(file, node), shown);
}

}  // namespace

Thresholds Thresholds::parseString(std::string_view text, const std::string& fileName) {
    toml::table root;
    try {
        root = toml::parse(text, fileName);
    } catch (const toml::parse_error& e) {
        throw core::InputError(fmt::format("{}:{}:{}: TOML syntax error: {}", fileName,
                                           e.source().begin.line, e.source().begin.column,
                                           e.description()));
    }
    Thresholds t;
    t.mFile = fileName;
    for (const auto& [k, node] : root) {
        const std::string key(k.str());
        if (key != "scenes") {
            walkNode(key, node, "", fileName, t.mGlobal);
            continue;
        }
        const auto* scenes = node.as_table();
        if (!scenes)
            throw core::InputError(
                fmt::format("{}: 'scenes' must be a table of per-scene tables ([scenes.NAME])",
                            whereOf(fileName, node)));
        for (const auto& [name, sceneNode] : *scenes) {
            const auto* sceneTable = sceneNode.as_table();
            if (!sceneTable)
                throw core::InputError(
                    fmt::format("{}: 'scenes.{}' must be a table ([scenes.{}]) of metric bounds",
                                whereOf(fileName, sceneNode), name.str(), name.str()));
            Bounds& b = t.mScenes[std::string(name.str())];
            for (const auto& [k, child] : *sceneTable)
                walkNode(std::string(k.str()), child, fmt::format("scenes.{}", name.str()),
                         fileName, b);
        }
    }
    checkConsistent(t.mGlobal);
    for (const auto& [name, b] : t.mScenes) checkConsistent(b);
    return t;
}

Thresholds Thresholds::parseFile(const fs::path& file) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
        throw core::InputError(
            fmt::format("{}: thresholds file not found; pass an existing TOML "
                        "file to --thresholds",
                        file.string()));
    std::ifstream in(file, std::ios::binary);
    if (!in.is_open())
        throw core::InputError(fmt::format("{}: cannot read the thresholds file", file.string()));
    std::ostringstream text;
    text << in.rdbuf();
    return parseString(text.str(), file.string());
}

Bounds sceneFileBounds(const core::ParameterTable& compareTable) {
    Bounds out;
    const std::string prefix = "thresholds.";
    for (const std::string& key : compareTable.keysUnder("thresholds")) {
        const auto* e = compareTable.find(key);
        std::optional<double> value;
        if (auto* d = std::get_if<double>(&e->value))
            value = *d;
        else if (auto* i = std::get_if<std::int64_t>(&e->value))
            value = static_cast<double>(*i);
        const std::string shown =
            compareTable.prefix().empty() ? key : compareTable.prefix() + "." + key;
        addBound(out, key.substr(prefix.size()), value,
                 e->where.empty() ? compareTable.file() : e->where, shown);
    }
    checkConsistent(out);
    return out;
}

Bounds mergeBounds(Bounds lower, const Bounds& higher) {
    for (const auto& [metric, hb] : higher) {
        MetricBounds& b = lower[metric];
        for (const auto& name : boundNames())
            if (slot(hb, name)) slot(b, name) = slot(hb, name);
    }
    return lower;
}

Bounds filterBounds(const Bounds& bounds, const std::function<bool(const std::string&)>& keep) {
    Bounds out;
    for (const auto& [metric, b] : bounds)
        if (keep(metric)) out.emplace(metric, b);
    return out;
}

Bounds Thresholds::forScene(const std::string& sceneName,
                            const core::ParameterTable* sceneTable) const {
    Bounds b = mGlobal;
    if (sceneTable) b = mergeBounds(std::move(b), sceneFileBounds(*sceneTable));
    if (auto it = mScenes.find(sceneName); it != mScenes.end())
        b = mergeBounds(std::move(b), it->second);
    return b;
}

std::vector<Check> evaluate(const MetricValues& metrics, const Bounds& bounds) {
    std::vector<Check> checks;
    for (const auto& [metric, b] : bounds) {
        const auto it = metrics.find(metric);
        for (const std::string& name : boundNames()) {
            const auto& limit = slot(b, name);
            if (!limit) continue;
            Check c;
            c.metric = metric;
            c.bound = name;
            c.limit = limit->value;
            c.where = limit->where;
            const std::string boundText =
                fmt::format("{} {} ({})", name, formatValue(limit->value), limit->where);
            if (it == metrics.end()) {
                c.value = std::nan("");
                c.status = Status::Fail;
                c.message = fmt::format(
                    "{} was not computed, but its {} is set; check the metric's name, or that "
                    "both renders have the buffers it needs",
                    metric, boundText);
                checks.push_back(std::move(c));
                continue;
            }
            c.value = it->second;
            if (std::isnan(c.value)) {
                c.status = Status::Fail;
                c.message = fmt::format("{} is not computable (NaN), so its {} cannot hold", metric,
                                        boundText);
                checks.push_back(std::move(c));
                continue;
            }
            const bool upper = name == "max" || name == "warn_max";
            const bool beyond = upper ? c.value > limit->value : c.value < limit->value;
            const bool warnOnly = name.rfind("warn_", 0) == 0;
            c.status = !beyond ? Status::Pass : warnOnly ? Status::Warn : Status::Fail;
            if (beyond)
                c.message = fmt::format("{} = {} is {} its {}", metric, formatValue(c.value),
                                        upper ? "above" : "below", boundText);
            else
                c.message = fmt::format("{} = {} is within its {}", metric, formatValue(c.value),
                                        boundText);
            checks.push_back(std::move(c));
        }
    }
    return checks;
}

}  // namespace twinrender::compare
