// Baselines: the metrics of a blessed run, and the check that no metric got worse than it
// (docs/design.md, "Thresholds and baselines"). Absolute bounds catch a bad render; the baseline
// catches a regression that is still inside them.
//
// A metric fails its baseline check when it got worse than the blessed value by more than
//     allowed = max(relative * |baseline - origin|, absolute)
// where "worse" follows the metric's direction (lower PSNR, SSIM or IoU; higher errors; for
// smoothness.ratio, further from 1) and `origin` is the metric's perfect value (0 for errors,
// 1 for SSIM and IoU), so the relative part is a fraction of the remaining error: an IoU of
// 0.99 may drop to 0.9898, not to 0.97. PSNR has no finite perfect value; its origin is 0 dB,
// so 2 % of 35 dB is 0.7 dB. The absolute part keeps near-perfect values (an id mismatch of 0)
// from failing on rounding. Defaults (defaultPolicy, from the metric table): relative 2 %,
// absolute the metric's noise in its unit. Both renderers are deterministic, so on one machine an
// unchanged build reproduces its metrics exactly; the tolerance is for other machines and drivers.
// Times (time.*) are recorded and their deltas reported but not checked by default: they
// depend on the machine and its load. A baseline file lists the policy of each of its metrics
// under "tolerances"; edit them there ("checked": true turns a time check on).
//
// Baseline file (JSON):
//   {"format": "twinrender-baseline", "version": 1, "blessed_from": "runs/x/summary.json",
//    "tolerances": {"beauty.flip": {"better": "lower", "origin": 0, "relative": 0.02,
//                                   "absolute": 0.001, "checked": true}, ...},
//    "scenes": {"planet": {"metrics": {"beauty.flip": 0.0612, ...}, "settings": {...}}}}
// Non-finite values are written as the strings "Infinity", "-Infinity" (JSON has no infinity;
// an identical pair has PSNR = +inf).
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "compare/metric_table.h"
#include "compare/thresholds.h"

namespace twinrender::compare {

// How one metric is held to its baseline.
struct BaselinePolicy {
    Better better = Better::Lower;
    double origin = 0.0;     // the perfect value, metric's unit; the relative tolerance is of
                             // |baseline - origin|; for Closer, the target
    double relative = 0.02;  // allowed worsening as a fraction of |baseline - origin|, >= 0
    double absolute = 1e-6;  // allowed worsening at least this, metric's unit, >= 0
    bool checked = true;     // false: recorded and shown with its delta, never fails
};

// The default policy of a metric: its direction, origin and noise in the metric table
// (metric_table.h), relative 2 %; times 25 % and not checked. BaselinePolicy{} for a metric
// the table does not know.
BaselinePolicy defaultPolicy(std::string_view metric);

// The worsening the policy allows from `baseline`, in the metric's unit. For a non-finite
// baseline (PSNR of an identical pair) only the absolute part.
double allowedWorsening(const BaselinePolicy& policy, double baseline);

struct BaselineScene {
    MetricValues metrics;     // finite values and +-inf; NaN values are never blessed
    nlohmann::json settings;  // the settings the scene was rendered with (may be null)
};

struct Baseline {
    std::string file;         // where it was read from, for messages; empty when made in memory
    std::string blessedFrom;  // the run it was blessed from
    std::map<std::string, BaselinePolicy> tolerances;  // metric -> policy
    std::map<std::string, BaselineScene> scenes;       // scene name -> blessed values

    // The file's policy for the metric, else defaultPolicy(metric).
    BaselinePolicy policy(const std::string& metric) const;
    // The blessed metrics of a scene; nullptr when the scene is not in the baseline.
    const MetricValues* metrics(const std::string& scene) const;
};

// A baseline from the contents of a run's summary.json (report_json.h's summaryJson): every
// scene's metrics (NaN ones left out) and settings, with the default policy of every metric.
// `source` is recorded as "blessed_from". Throws core::InputError naming `source` and the JSON
// path when the summary is malformed.
Baseline bless(const nlohmann::json& summary, const std::string& source = "");
// bless() of RUN_DIR/summary.json; throws core::InputError when it is missing or unreadable.
Baseline blessRunDir(const std::filesystem::path& runDir);

nlohmann::json toJson(const Baseline& baseline);
// Throws core::InputError naming `file` and the key for anything that is not a baseline
// (wrong format tag, newer version, unknown keys, non-numeric values, negative tolerances).
Baseline parseBaseline(const nlohmann::json& json, const std::string& file);
Baseline readBaseline(const std::filesystem::path& file);
// Atomic write (temporary name, then rename), pretty-printed.
void writeBaseline(const Baseline& baseline, const std::filesystem::path& file);

// One check with bound "baseline" per checked metric of the scene's baseline: Fail when the
// metric got worse by more than its tolerance, when it is NaN, or when it is no longer
// computed; Pass otherwise (better, or worse within the tolerance). The message names the
// metric, the baseline value, the new value and the delta, and for a failure the tolerance
// and, when `settings` is given, the settings that changed since the baseline. Check::limit
// is the worst value the tolerance allows, Check::baseline the blessed value. Empty when the
// scene is not in the baseline (a new scene), or the baseline has no checked metric for it;
// metrics the baseline does not know are not checked.
std::vector<Check> compareToBaseline(const std::string& scene, const MetricValues& metrics,
                                     const Baseline& baseline,
                                     const nlohmann::json* settings = nullptr);

// The change of a metric from its blessed value, for tables: "+0.0422 (+35.1 %)", the
// percentage only where it is defined (a finite, non-zero baseline and a non-zero change).
std::string changeText(double value, double baseline);

// The differences between two settings objects, one line per dotted key:
// "realtime.ssss.enabled: true -> false", "raymarch.level: added (0.2)", "x: removed".
std::vector<std::string> settingsChanges(const nlohmann::json& before, const nlohmann::json& after);

}  // namespace twinrender::compare
