#include "report/error_split_view.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "report/markup.h"

namespace twinrender::report {

using compare::formatValue;

namespace {

struct Part {
    const char* key;
    const char* name;     // on the scene page
    const char* short_;   // in an index cell
    const char* meaning;  // what the part's error measures
};
constexpr Part PARTS[] = {
    {"surface.beauty.flip", "surface", "surface",
     "the screen-space surface, under the exact light"},
    {"lighting.beauty.flip", "lighting", "light",
     "the real-time shadow, occlusion and glow, on the exact surface"},
    {"shading.beauty.flip", "shading", "shading", "the floor: the exact surface and light"},
};

double valueOr(const MetricValues& m, const std::string& key, double fallback) {
    const auto it = m.find(key);
    return it == m.end() || !std::isfinite(it->second) ? fallback : it->second;
}

std::string barRow(const std::string& cls, const std::string& label, double value, double scale,
                   bool withValue, const std::string& title) {
    const double width = scale > 0.0 ? std::clamp(100.0 * value / scale, 0.0, 100.0) : 0.0;
    return fmt::format(
        "<div class=\"split-row {}\" title=\"{}\"><span class=\"split-label\">{}</span><span "
        "class=\"split-track\"><span class=\"split-bar\" style=\"width:{:.1f}%\"></span></span>{}"
        "</div>",
        cls, htmlEscape(title), htmlEscape(label), width,
        withValue ? "<span class=\"split-value\">" + htmlEscape(formatValue(value)) + "</span>"
                  : "");
}

}  // namespace

bool hasErrorSplit(const MetricValues& metrics) {
    for (const Part& p : PARTS)
        if (!metrics.count(p.key)) return false;
    return true;
}

std::string errorSplitBars(const MetricValues& metrics, bool compact) {
    if (!hasErrorSplit(metrics)) return "";
    const double whole = valueOr(metrics, "beauty.flip", 0.0);
    double scale = whole;
    for (const Part& p : PARTS) scale = std::max(scale, valueOr(metrics, p.key, 0.0));
    std::string h = fmt::format("<div class=\"split{}\">", compact ? " compact" : "");
    if (!compact)
        h += barRow("whole", "whole image", whole, scale, true,
                    "beauty.flip: the real-time image against the reference");
    for (const Part& p : PARTS) {
        const double v = valueOr(metrics, p.key, NAN);
        h += barRow(p.name, compact ? p.short_ : p.name, std::isfinite(v) ? v : 0.0, scale,
                    !compact, fmt::format("{} = {}: {}", p.key, formatValue(v), p.meaning));
    }
    h += "</div>";
    if (!compact)
        h += "<p class=\"note\">ꟻLIP of the real-time shading with one part of the input "
             "taken from the reference (docs/design.md, \"The error split\"): the longest bar "
             "is where most of the error comes from. The parts do not add up to the whole "
             "(ꟻLIP is not additive).</p>";
    return h;
}

}  // namespace twinrender::report
