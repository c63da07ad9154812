// A study's rows seen per setting across the scenes its points span (the methods study,
// docs/methods.md): for each setting (a series and an x), the median over the scenes of every
// metric and stage time, and the settings that no other one beats in both time and error.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "report/study_report.h"

namespace twinrender::report {

using compare::MetricValues;

// The median of the finite values (the mean of the middle two for an even count); NaN when
// there are none.
double median(std::vector<double> values);

struct SettingMedians {
    std::string series;
    double x = 0.0;
    std::vector<std::string> scenes;          // the scenes whose rows went in, in row order
    MetricValues metrics;                     // per metric, the median over those scenes
    std::map<std::string, double> timingsMs;  // per stage and "total", the median likewise
};

// The settings of `rows` in order of first appearance, each the median over its rows (one per
// scene). Rows with an error take no part.
std::vector<SettingMedians> mediansOverScenes(const std::vector<const StudyRow*>& rows);

// The indices of the settings on the Pareto front of the median total time against the
// median of `metric` (as a sweep's chart takes it: sweep_report.h chartValue and
// lowerIsBetter), by increasing time (svg_chart.h paretoFront).
std::vector<std::size_t> settingsFront(const std::vector<SettingMedians>& settings,
                                       const std::string& metric);

}  // namespace twinrender::report
