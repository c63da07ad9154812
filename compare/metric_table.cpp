#include "compare/metric_table.h"

namespace twinrender::compare {

std::string metricUnit(std::string_view metric) {
    auto ends = [&](std::string_view s) {
        return metric.size() >= s.size() && metric.substr(metric.size() - s.size()) == s;
    };
    if (ends("psnr")) return "dB";
    if (ends("_deg")) return "°";
    if (ends("_px")) return "px";
    if (ends("_ms")) return "ms";
    return "";
}

}  // namespace twinrender::compare
