// Metric thresholds: the absolute bounds a CI run holds each metric to (docs/design.md, "Thresholds
// and baselines"), and the verdict they give.
//
// A thresholds file (TOML) names metrics and their bounds, with per-scene overrides:
//
//     "beauty.flip" = { max = 0.15, warn_max = 0.10 }
//     "shadow.iou"  = { min = 0.90 }
//     [scenes.ringworld]
//     "shadow.iou"  = { min = 0.80 }
//
// Bounds are `max` and `min` (beyond them: fail) and `warn_max` and `warn_min` (beyond them:
// warn). Bounds are inclusive: a value equal to its max passes. Unquoted dotted keys
// (beauty.flip = {...}) and standard tables (["beauty.flip"]) mean the same. A scene file may
// carry its own bounds under [compare.thresholds], in the same form.
//
// Precedence, per metric and per bound (most specific wins):
//     thresholds file, top level   <   scene file [compare.thresholds]
//                                  <   thresholds file [scenes.NAME]
// The scene file's own bounds beat the shared defaults, since they were written for that one
// scene; the thresholds file's [scenes.NAME] table beats the scene file, so whoever runs the CI
// can tighten or loosen one scene without editing its scene file. Overrides replace single
// bounds: [scenes.NAME] "beauty.flip" = { max = 0.2 } keeps the global warn_max.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/parameters.h"

namespace twinrender::compare {

// Metric name -> value, as computed (docs/design.md, "Metrics"). NaN: not computable.
using MetricValues = std::map<std::string, double>;

// Ordered from best to worst, so the verdict of several checks is the largest.
enum class Status { Pass = 0, Warn = 1, Fail = 2 };

// "pass", "warn", "fail".
std::string_view toString(Status status);
// "pass" | "warn" | "fail" -> Status; nullopt for anything else.
std::optional<Status> statusFromString(std::string_view text);
Status worst(Status a, Status b);

// One bound of one metric and where it was set ("thresholds.toml:3:25").
struct Limit {
    double value = 0.0;
    std::string where;
};

struct MetricBounds {
    std::optional<Limit> max;      // fail above
    std::optional<Limit> min;      // fail below
    std::optional<Limit> warnMax;  // warn above
    std::optional<Limit> warnMin;  // warn below
};

// Metric name -> its bounds, for one scene.
using Bounds = std::map<std::string, MetricBounds>;

// The bound names a thresholds table accepts, in the order checks are listed.
const std::vector<std::string>& boundNames();

// The outcome of holding one metric to one bound.
struct Check {
    std::string metric;  // "beauty.flip"
    double value = 0.0;  // the metric's value; NaN when missing or not computable
    std::string bound;   // "max" | "min" | "warn_max" | "warn_min" | "baseline"
    double limit = 0.0;  // the bound; for "baseline", the worst value the tolerance allows
    Status status = Status::Pass;
    std::string message;  // one readable sentence, also for passes
    std::string where;    // where the bound was set (file:line:column, or the baseline file)
    // Only for bound == "baseline": the blessed value (value - baseline is the delta).
    std::optional<double> baseline;
};

// The worst status of the checks; Pass when there are none.
Status overallStatus(const std::vector<Check>& checks);

class Thresholds {
  public:
    // Throws core::InputError naming the file, line and key for an unreadable file, a TOML
    // syntax error, an unknown bound name, a non-numeric or non-finite value, or a warn bound
    // beyond its fail bound (warn_max > max, warn_min < min) in the same table.
    static Thresholds parseFile(const std::filesystem::path& file);
    // `fileName` is used in messages.
    static Thresholds parseString(std::string_view text, const std::string& fileName);

    // The bounds for one scene, merged with the precedence above. `sceneTable` is the scene
    // file's [compare] table (core::Scene::compare); its keys under "thresholds." are marked
    // read ("thresholds.beauty.flip.max" -> metric "beauty.flip", bound "max"). Throws
    // core::InputError for a bad key there, naming its file:line:column.
    Bounds forScene(const std::string& sceneName,
                    const core::ParameterTable* sceneTable = nullptr) const;

    const Bounds& global() const { return mGlobal; }
    // [scenes.NAME] tables by scene name. A name no scene has is not an error here (a run
    // may cover a subset of the suite); callers that know the whole suite may check.
    const std::map<std::string, Bounds>& scenes() const { return mScenes; }
    const std::string& file() const { return mFile; }

  private:
    std::string mFile;
    Bounds mGlobal;
    std::map<std::string, Bounds> mScenes;
};

// The bounds a scene file sets under [compare.thresholds] (keys "thresholds.METRIC.BOUND" of
// the [compare] table); empty when it sets none. Throws core::InputError as parseFile does.
Bounds sceneFileBounds(const core::ParameterTable& compareTable);

// `higher` over `lower`, bound by bound.
Bounds mergeBounds(Bounds lower, const Bounds& higher);

// The bounds whose metric `keep` accepts (e.g. only "beauty." metrics when comparing plain
// images, which have no other buffers).
Bounds filterBounds(const Bounds& bounds, const std::function<bool(const std::string&)>& keep);

// One check per metric and bound, ordered by metric name, then max, min, warn_max, warn_min.
// A value beyond a fail bound fails, beyond a warn bound warns, else passes; a NaN value, or a
// metric named in `bounds` but absent from `metrics`, fails every one of its bounds. Metrics
// without bounds are not checked.
std::vector<Check> evaluate(const MetricValues& metrics, const Bounds& bounds);

// A number for messages and tables: 4 significant digits, no exponent for ordinary sizes.
std::string formatValue(double value);
// A number for machines (CSV, JUnit properties): the shortest form that reads back to the
// same double; "nan", "inf", "-inf" for non-finite ones.
std::string exactValue(double value);

}  // namespace twinrender::compare
