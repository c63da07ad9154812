// Every metric twinrender reports, in one table (docs/design.md, "Metrics"): its key, the
// unit it is shown in, which way is better, the AOV buffer it reads, which code writes it and
// what it means. The metrics, thresholds, baselines, reports, sweeps and studies all read it;
// its order is the order of every metric table and column list.
//
// Two entries are families, their variable part named in angle brackets:
// time.<renderer>_ms (time.realtime_ms, time.raymarch_ms, and a third renderer's) and
// count.<counter> (the test render's counters in sweeps and studies).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace twinrender::compare {

enum class Better {
    Higher,  // PSNR, SSIM, IoU
    Lower,   // errors, mismatches, times, counts
    Closer,  // closer to the metric's origin (smoothness.ratio: 1)
};

// "higher", "lower", "closer".
std::string_view toString(Better better);

// Which code writes a metric, so which results have it.
enum class MetricSource {
    AnyPair,   // computeMetrics, for every pair (AOV images and plain images alike)
    AovPair,   // computeMetrics, for pairs of AOV images only
    Render,    // the commands that render: the renders' times and counters, the error split
    Study,     // the stability studies that ask for it (app/studies.h)
    Sequence,  // a sequence scene (`run`, app/sequence_run.h): per frame, or over its frames
};

struct MetricInfo {
    std::string_view key;   // "beauty.flip"; a family's variable part in <>
    std::string_view unit;  // for display: "dB", "°", "px", "ms"; "" for ratios and fractions
    Better better;
    // The perfect value where it is finite (0 for errors, 1 for SSIM and IoU, the target of
    // Closer); 0 dB for PSNR. A baseline's relative tolerance is a fraction of the distance to it.
    double origin;
    // About the rounding noise of the metric, in its unit: a change smaller than this is not
    // a regression anyone could see (a baseline's absolute tolerance).
    double noise;
    // The AOV buffer it reads (docs/design.md, "The frame"): "beauty" (R, G, B tonemapped), "A",
    // "Z", "N", "uv", "id", "emission", "shadow", "ao"; "" for none (times, counters).
    std::string_view buffer;
    MetricSource source;
    bool overview;             // a column of the run's index page
    bool machineDependent;     // measured anew on each machine and load (times): never checked
                               // against a baseline by default
    std::string_view meaning;  // one line
};

// Every metric, in display order.
const std::vector<MetricInfo>& metricTable();

// The entry of a key: its own, else the family it belongs to; nullptr for an unknown key.
const MetricInfo* findMetric(std::string_view key);

// The keys of the table, comma-separated, families as patterns: for messages. Only those
// computeMetrics writes when `comparisonOnly`.
std::string metricNames(bool comparisonOnly = false);

// The meaning and the better direction, for a tooltip: "... (lower is better)"; "" for an
// unknown key.
std::string metricDescription(std::string_view key);

// The metric's unit for tables ("dB", "°", "px", "ms"); "" for ratios, fractions and unknown
// keys.
std::string metricUnit(std::string_view key);

// Display order: the table's, a family's members by name, unknown keys last by name.
bool metricLess(std::string_view a, std::string_view b);
// `keys` in display order.
std::vector<std::string> inMetricOrder(std::vector<std::string> keys);

// True when computeMetrics writes the metric (for AOV images, or for every pair).
bool computedByComparison(std::string_view key);
// True when computeMetrics writes the metric for plain images (PNGs) too.
bool computedOnPlainImages(std::string_view key);

}  // namespace twinrender::compare
