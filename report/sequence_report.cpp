#include "report/sequence_report.h"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <set>
#include <vector>

#include "compare/metric_table.h"
#include "core/image_io.h"
#include "core/write_roots.h"
#include "report/html_page.h"
#include "report/markup.h"
#include "report/sequence_summary.h"
#include "report/study_report.h"
#include "report/svg_chart.h"

namespace twinrender::report {

using compare::formatValue;
using compare::inMetricOrder;
using compare::metricUnit;

namespace fs = std::filesystem;

namespace {

// Metrics drawn dashed in another's chart: the reference's change beside the real-time one.
const std::map<std::string, std::string>& referenceCompanions() {
    static const std::map<std::string, std::string> m = {
        {"temporal.frame_flip", "temporal.reference_frame_flip"},
        {"temporal.normal_change_deg", "temporal.reference_normal_change_deg"}};
    return m;
}

std::vector<std::string> frameMetrics(const SequenceReport& q) {
    std::set<std::string> keys;
    for (const SequenceFrame& f : q.frames)
        for (const auto& [k, v] : f.metrics) keys.insert(k);
    return inMetricOrder({keys.begin(), keys.end()});
}

LineSeries seriesOf(const SequenceReport& q, const std::string& metric, const std::string& name,
                    bool dashed) {
    LineSeries s{name, {}, dashed};
    for (const SequenceFrame& f : q.frames) {
        const auto it = f.metrics.find(metric);
        s.points.push_back({double(f.frame), it == f.metrics.end() ? NAN : it->second,
                            fmt::format("frame {}", f.frame)});
    }
    return s;
}

std::string chartFile(const std::string& metric) {
    return "charts/" + metric + ".svg";
}

// A chart with nothing to show: the metric does not apply to any frame, or no frame's finite
// value differs from another's.
bool flatOrNotApplicable(const SequenceReport& q, const std::string& metric) {
    const auto na = notApplicableInEvery(q.frames);
    if (na.count(metric)) return true;
    std::optional<double> first;
    for (const SequenceFrame& f : q.frames) {
        const auto it = f.metrics.find(metric);
        if (it == f.metrics.end() || !std::isfinite(it->second)) continue;
        if (first && *first != it->second) return false;
        first = it->second;
    }
    return true;
}

}  // namespace

std::map<std::string, std::string> writeSequenceCharts(const SequenceReport& q, const fs::path& dir,
                                                       const compare::Bounds& bounds) {
    std::map<std::string, std::string> charts;
    std::set<std::string> companions;
    for (const auto& [m, ref] : referenceCompanions()) companions.insert(ref);
    core::makeFolders(dir / "charts");
    for (const std::string& m : frameMetrics(q)) {
        if (companions.count(m) || flatOrNotApplicable(q, m)) continue;
        LineChart c;
        c.title = m + " over the frames";
        c.xLabel = "frame";
        const std::string unit = metricUnit(m);
        c.yLabel = unit.empty() ? m : fmt::format("{} ({})", m, unit);
        c.width = 520;
        c.height = 320;
        c.yMarks = boundMarks(bounds, m);
        const auto companion = referenceCompanions().find(m);
        c.series.push_back(
            seriesOf(q, m, companion == referenceCompanions().end() ? m : "real-time", false));
        if (companion != referenceCompanions().end())
            c.series.push_back(seriesOf(q, companion->second, "reference", true));
        core::writeTextFile(dir / chartFile(m), lineSvg(c));
        charts[m] = chartFile(m);
    }
    return charts;
}

std::string sequenceSection(const SceneReport& s) {
    if (!s.sequence) return "";
    const SequenceReport& q = *s.sequence;
    std::string h = "<section id=\"sequence\">\n<h2>Sequence</h2>\n";
    const double seconds = double(q.frames.size()) / q.fps;
    h += fmt::format(
        "<p class=\"note\">{} frames ({} to {}) at {} frames per second: {} s. Flicker is what "
        "the real-time frames change from one frame to the next that the reference does not "
        "(temporal.flicker: their frame-to-frame ꟻLIP minus the reference's). The images below "
        "are frame {}, the one with the largest ꟻLIP.</p>\n",
        q.frames.size(), q.frames.empty() ? 0 : q.frames.front().frame,
        q.frames.empty() ? 0 : q.frames.back().frame, formatValue(q.fps), formatValue(seconds),
        q.shownFrame);
    if (!q.videos.empty()) {
        h += "<figure class=\"sequence-video\"><video id=\"sequence-video\" controls loop muted "
             "playsinline preload=\"metadata\" "
             "style=\"width:100%;max-width:1200px;image-rendering:pixelated\">";
        // WebM first: every browser with VP9 takes it; the MP4 (H.264) is for the others.
        for (const char* type : {"video/webm", "video/mp4"})
            if (const auto it = q.videos.find(type); it != q.videos.end())
                h += fmt::format("<source src=\"{}\" type=\"{}\">", urlPath(it->second), type);
        h += "</video><figcaption><b>real-time | reference | ꟻLIP map</b><span>";
        for (const auto& [type, file] : q.videos)
            h += fmt::format(" <a href=\"{}\">{}</a>", urlPath(file), htmlEscape(file));
        h += "</span></figcaption></figure>\n";
    }
    if (!q.charts.empty()) {
        h += "<div class=\"charts\" style=\"display:flex;flex-wrap:wrap;gap:0.5rem\">\n";
        for (const std::string& m : inMetricOrder([&] {
                 std::vector<std::string> k;
                 for (const auto& [metric, file] : q.charts) k.push_back(metric);
                 return k;
             }()))
            h += fmt::format("<img src=\"{}\" alt=\"{} over the frames\" width=\"520\">",
                             urlPath(q.charts.at(m)), htmlEscape(m));
        h += "</div>\n";
    }
    // The metrics that do not apply to any frame are left out (the metrics table says n/a).
    std::vector<std::string> metrics = frameMetrics(q);
    std::erase_if(metrics, [na = notApplicableInEvery(q.frames)](const std::string& m) {
        return na.count(m) > 0;
    });
    h += "<div style=\"overflow-x:auto\"><table class=\"frames\">\n<thead><tr><th>frame</th>";
    for (const std::string& m : metrics) h += metricHeaderCell(m);
    h += "</tr></thead>\n<tbody>\n";
    for (const SequenceFrame& f : q.frames) {
        h += fmt::format("<tr{}><td>{}</td>", f.frame == q.shownFrame ? " class=\"shown\"" : "",
                         f.frame);
        for (const std::string& m : metrics) h += metricValueCell(f.metrics, m, false);
        h += "</tr>\n";
    }
    return h + "</tbody></table></div>\n</section>\n";
}

}  // namespace twinrender::report
