#include "report/study_summary.h"

#include <algorithm>
#include <cmath>

#include "report/svg_chart.h"
#include "report/sweep_report.h"

namespace twinrender::report {

double median(std::vector<double> values) {
    std::erase_if(values, [](double v) { return !std::isfinite(v); });
    if (values.empty()) return NAN;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::vector<SettingMedians> mediansOverScenes(const std::vector<const StudyRow*>& rows) {
    std::vector<SettingMedians> out;
    std::vector<std::vector<const StudyRow*>> members;
    for (const StudyRow* r : rows) {
        if (!r->error.empty()) continue;
        auto it = std::find_if(out.begin(), out.end(), [&](const SettingMedians& s) {
            return s.series == r->series && s.x == r->x;
        });
        if (it == out.end()) {
            out.push_back({r->series, r->x, {}, {}, {}});
            members.emplace_back();
            it = std::prev(out.end());
        }
        it->scenes.push_back(r->scene);
        members[static_cast<std::size_t>(it - out.begin())].push_back(r);
    }
    for (std::size_t i = 0; i < out.size(); ++i) {
        std::map<std::string, std::vector<double>> metrics, times;
        for (const StudyRow* r : members[i]) {
            for (const auto& [k, v] : r->metrics) metrics[k].push_back(v);
            for (const auto& [k, v] : r->timingsMs) times[k].push_back(v);
        }
        for (auto& [k, v] : metrics) out[i].metrics[k] = median(std::move(v));
        for (auto& [k, v] : times) out[i].timingsMs[k] = median(std::move(v));
    }
    return out;
}

std::vector<std::size_t> settingsFront(const std::vector<SettingMedians>& settings,
                                       const std::string& metric) {
    std::vector<ChartPoint> points;
    for (const SettingMedians& s : settings) {
        const auto t = s.timingsMs.find("total");
        const auto m = s.metrics.find(metric);
        points.push_back({t == s.timingsMs.end() ? NAN : t->second,
                          m == s.metrics.end() ? NAN : chartValue(metric, m->second), ""});
    }
    return paretoFront(points, lowerIsBetter(metric));
}

}  // namespace twinrender::report
