#include "report/sequence_summary.h"

#include <cmath>
#include <set>

#include "compare/metric_table.h"
#include "report/study_summary.h"

namespace twinrender::report {

using compare::Better;
using compare::findMetric;
using compare::MetricInfo;
using compare::MetricValues;
using compare::worst;

namespace {

// The per-frame temporal metrics summarised by their mean and largest value, as
// {per-frame key, mean key, max key}.
struct Pooled {
    const char* frame;
    const char* mean;
    const char* max;
};
constexpr Pooled POOLED[] = {
    {"temporal.flicker", "temporal.flicker_mean", "temporal.flicker_max"},
    {"temporal.normal_flicker_deg", "temporal.normal_flicker_mean_deg",
     "temporal.normal_flicker_max_deg"},
};

// Whether `a` is worse than `b` for the metric.
bool worse(const MetricInfo* info, double a, double b) {
    if (!info) return a > b;
    switch (info->better) {
        case Better::Higher:
            return a < b;
        case Better::Lower:
            return a > b;
        case Better::Closer:
            return std::abs(a - info->origin) > std::abs(b - info->origin);
    }
    return a > b;
}

}  // namespace

MetricValues summariseSequence(const std::vector<SequenceFrame>& frames) {
    std::set<std::string> keys;
    for (const SequenceFrame& f : frames)
        for (const auto& [k, v] : f.metrics) keys.insert(k);
    MetricValues out;
    for (const std::string& key : keys) {
        std::vector<double> values;
        for (const SequenceFrame& f : frames)
            if (const auto it = f.metrics.find(key);
                it != f.metrics.end() && !std::isnan(it->second))
                values.push_back(it->second);
        const MetricInfo* info = findMetric(key);
        if (key.starts_with("temporal.")) {
            for (const Pooled& p : POOLED)
                if (key == p.frame) {
                    double sum = 0.0, most = NAN;
                    for (double v : values) {
                        sum += v;
                        if (std::isnan(most) || v > most) most = v;
                    }
                    out[p.mean] = values.empty() ? NAN : sum / double(values.size());
                    out[p.max] = most;
                }
            continue;
        }
        if (values.empty()) {
            out[key] = NAN;
        } else if (info && info->machineDependent) {
            out[key] = median(values);
        } else {
            double w = values.front();
            for (double v : values)
                if (worse(info, v, w)) w = v;
            out[key] = w;
        }
    }
    return out;
}

std::vector<std::string> pooledTemporalMetrics() {
    std::vector<std::string> keys;
    for (const Pooled& p : POOLED) keys.insert(keys.end(), {p.mean, p.max});
    return keys;
}

std::int64_t worstFrame(const std::vector<SequenceFrame>& frames) {
    if (frames.empty()) return 0;
    std::int64_t worst = frames.front().frame;
    double most = -INFINITY;
    for (const SequenceFrame& f : frames)
        if (const auto it = f.metrics.find("beauty.flip");
            it != f.metrics.end() && it->second > most) {
            most = it->second;
            worst = f.frame;
        }
    return worst;
}

std::map<std::string, std::string> notApplicableInEvery(const std::vector<SequenceFrame>& frames) {
    if (frames.empty()) return {};
    std::map<std::string, std::string> out = frames.front().notApplicable;
    for (const SequenceFrame& f : frames)
        std::erase_if(out, [&](const auto& entry) { return !f.notApplicable.count(entry.first); });
    return out;
}

}  // namespace twinrender::report
