#include "report/index_page.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "compare/metric_table.h"
#include "report/error_split_view.h"
#include "report/html_page.h"
#include "report/markup.h"
#include "report/scene_facts.h"

namespace twinrender::report {

using compare::Check;
using compare::MetricInfo;
using compare::metricTable;
using compare::Status;
using compare::toString;

namespace {

bool sceneHas(const SceneReport& s, const std::string& metric) {
    if (s.metrics.count(metric)) return true;
    return std::any_of(s.checks.begin(), s.checks.end(),
                       [&](const Check& c) { return c.metric == metric; });
}

// The overview metrics of the table that any scene has, in its order.
std::vector<std::string> overviewColumns(const RunReport& run) {
    std::vector<std::string> columns;
    for (const MetricInfo& info : metricTable()) {
        if (!info.overview) continue;
        const std::string m(info.key);
        if (std::any_of(run.scenes.begin(), run.scenes.end(),
                        [&](const SceneReport& s) { return sceneHas(s, m); }))
            columns.push_back(m);
    }
    return columns;
}

// The headline metrics any scene has.
std::vector<std::string> headlineColumns(const RunReport& run) {
    std::vector<std::string> columns;
    for (const char* m : INDEX_HEADLINE)
        if (std::any_of(run.scenes.begin(), run.scenes.end(),
                        [&](const SceneReport& s) { return sceneHas(s, m); }))
            columns.push_back(m);
    return columns;
}

// Each renderer's devices over the scenes, in the pages' order: {label, devices}.
std::vector<std::pair<std::string, std::set<std::string>>> devicesOf(const RunReport& run) {
    std::vector<std::pair<std::string, std::set<std::string>>> out;
    for (const SceneReport& s : run.scenes)
        for (const std::string& r : renderersOf(s)) {
            const std::string device = deviceOf(s, r), label = rendererLabel(s, r);
            if (device.empty()) continue;
            auto it = std::find_if(out.begin(), out.end(),
                                   [&](const auto& e) { return e.first == label; });
            if (it == out.end()) it = out.insert(out.end(), {label, {}});
            it->second.insert(device);
        }
    return out;
}

std::string indexHeader(const RunReport& run) {
    std::vector<Status> sceneStatuses;
    for (const auto& s : run.scenes) sceneStatuses.push_back(s.status());
    std::vector<std::string> facts = {htmlEscape(countsText(sceneStatuses, "scene"))};
    for (const auto& [label, devices] : devicesOf(run)) {
        std::string names;
        for (const std::string& d : devices) names += (names.empty() ? "" : ", ") + d;
        facts.push_back(htmlEscape(label) + " on <b class=\"device\">" + htmlEscape(names) +
                        "</b>");
    }
    if (!run.createdAt.empty()) facts.push_back(htmlEscape(run.createdAt));
    if (!run.thresholdsFile.empty())
        facts.push_back("thresholds <code>" + htmlEscape(run.thresholdsFile) + "</code>");
    facts.push_back(run.baselineFile.empty()
                        ? std::string("no baseline")
                        : "baseline <code>" + htmlEscape(run.baselineFile) + "</code>");
    for (const auto& [text, href] : run.links)
        facts.push_back("<a href=\"" + urlPath(href) + "\">" + htmlEscape(text) + "</a>");
    return pageHeader(run.title, run.status(), facts);
}

// The first beauty render of the scene, linked to its page; empty when it has none.
std::string thumbnail(const SceneReport& s, const std::string& page) {
    for (const std::string& r : renderersOf(s)) {
        auto it = s.renderers.find(r);
        if (it == s.renderers.end()) continue;
        auto img = it->second.images.find("beauty");
        if (img == it->second.images.end()) continue;
        return fmt::format("<a href=\"{}\"><img class=\"thumb\" src=\"{}\" alt=\"{} {}\"></a>",
                           page, urlPath(s.name + "/" + img->second), htmlEscape(s.name),
                           htmlEscape(rendererLabel(s, r)));
    }
    return "";
}

std::string pageOf(const SceneReport& s) {
    return urlPath(s.name) + "/index.html";
}

// The scene's name linked to its page, and its description.
std::string sceneCell(const SceneReport& s) {
    return fmt::format(
        "<td class=\"scene\"><a href=\"{}\">{}</a>{}</td>", pageOf(s), htmlEscape(s.name),
        s.description.empty() ? "" : "<div class=\"desc\">" + htmlEscape(s.description) + "</div>");
}

// The measured renderer's and the reference's times and their ratio.
std::string timeCells(const SceneReport& s) {
    const auto rt = sceneTimeMs(s, testRenderer(s)), ref = sceneTimeMs(s, "raymarch");
    const std::string basis = timeBasis(s);
    const std::string title = basis.empty() ? "" : " title=\"" + htmlEscape(basis) + "\"";
    return fmt::format(
        "<td class=\"num time\"{0}>{1}</td><td class=\"num\"{0}>{2}</td><td class=\"num\">{3}"
        "</td>",
        title, rt ? htmlEscape(formatMs(*rt)) : "—", ref ? htmlEscape(formatMs(*ref)) : "—",
        htmlEscape(speedRatio(s)));
}

// A scene's row, and the row of its problems under it (across the metric columns) if any.
std::string sceneRow(const RunReport& run, const SceneReport& s,
                     const std::vector<std::string>& columns, bool split) {
    const auto problems = problemsOf(s);
    std::string h =
        fmt::format("<tr{}><td>{}</td>", problems.empty() ? "" : " class=\"has-problems\"",
                    thumbnail(s, pageOf(s)));
    h += sceneCell(s) + "<td>" + badge(s.status()) + "</td>";
    for (const auto& m : columns) h += valueCell(s, m, run.thresholdsFile);
    if (split)
        h += hasErrorSplit(s.metrics)
                 ? "<td class=\"split-cell\">" + errorSplitBars(s.metrics, true) + "</td>"
                 : std::string(
                       "<td class=\"muted\" title=\"no error split measured for this scene "
                       "(a sequence's frames are not split)\">—</td>");
    h += timeCells(s) + "</tr>\n";
    if (problems.empty()) return h;
    h += fmt::format("<tr class=\"problems\"><td colspan=\"2\"></td><td colspan=\"{}\"><ul>",
                     columns.size() + 4 + (split ? 1 : 0));
    const std::size_t shown = problems.size() > 4 ? 3 : problems.size();
    for (std::size_t i = 0; i < shown; ++i)
        h += fmt::format("<li class=\"{}\">{}</li>", toString(problems[i].first),
                         htmlEscape(problems[i].second));
    if (problems.size() > shown)
        h += fmt::format("<li><a href=\"{}\">{} more on the scene page</a></li>", pageOf(s),
                         problems.size() - shown);
    return h + "</ul></td></tr>\n";
}

std::string timeHeaders(const RunReport& run) {
    return "<th class=\"num\">" + htmlEscape(runTestLabel(run)) +
           " <span class=\"unit\">ms</span></th>"
           "<th class=\"num\">Reference <span class=\"unit\">ms</span></th>"
           "<th class=\"num\" title=\"the reference's time over the measured renderer's\">"
           "Speed-up</th>";
}

std::string scenesTable(const RunReport& run) {
    const std::vector<std::string> columns = headlineColumns(run);
    const bool split = std::any_of(run.scenes.begin(), run.scenes.end(),
                                   [](const SceneReport& s) { return hasErrorSplit(s.metrics); });
    std::string h =
        "<div class=\"fit\"><table class=\"scenes\" id=\"scenes\" data-fit>\n<thead><tr><th></th>"
        "<th>Scene</th><th>Verdict</th>";
    for (const auto& m : columns) h += metricHeaderCell(m);
    if (split)
        h += "<th title=\"ꟻLIP of the real-time shading given the reference's surface or "
             "light: the longest bar is where the error comes from\">Error from</th>";
    h += timeHeaders(run) + "</tr></thead>\n<tbody>\n";
    for (const SceneReport& s : run.scenes) h += sceneRow(run, s, columns, split);
    h += "</tbody></table></div>\n";
    h += "<div class=\"legend-row\"><span><span class=\"swatch pass\"></span>within its "
         "bounds</span><span><span class=\"swatch warn\"></span>beyond a warn bound</span>"
         "<span><span class=\"swatch fail\"></span>beyond a fail bound or the baseline</span>"
         "<span>uncoloured: no bound set; n/a: does not apply. Times: total render, without "
         "start-up and file I/O; a sequence's, the median over its frames.</span></div>\n";
    return h;
}

// Every overview metric: a table that scrolls sideways under its sticky scene column.
std::string allMetricsTable(const RunReport& run) {
    const std::vector<std::string> columns = overviewColumns(run);
    std::string h = fmt::format(
        "<details class=\"all-metrics\"><summary>Every overview metric ({} columns; each "
        "scene's page has all of them)</summary>\n<p class=\"scroll-hint\">Scroll sideways "
        "for more columns →</p>\n<div class=\"scroll\"><table class=\"scenes-all\">\n<thead>"
        "<tr><th class=\"sticky\">Scene</th><th>Verdict</th>",
        columns.size());
    for (const auto& m : columns) h += metricHeaderCell(m);
    h += timeHeaders(run) + "</tr></thead>\n<tbody>\n";
    for (const SceneReport& s : run.scenes) {
        h += fmt::format("<tr><td class=\"sticky\"><a href=\"{}\">{}</a></td><td>{}</td>",
                         pageOf(s), htmlEscape(s.name), badge(s.status()));
        for (const auto& m : columns) h += valueCell(s, m, run.thresholdsFile);
        h += timeCells(s) + "</tr>\n";
    }
    return h + "</tbody></table></div></details>\n";
}

// The plain words where the real-time renderer ran on a software rasteriser.
std::string deviceNotes(const RunReport& run) {
    std::set<std::string> software;
    for (const SceneReport& s : run.scenes)
        if (ranOnSoftwareRasteriser(s)) software.insert(deviceOf(s, "realtime"));
    std::string h;
    for (const std::string& d : software) h += softwareRasteriserNote(d);
    return h;
}

}  // namespace

std::string indexPage(const RunReport& run) {
    std::string h = pageHead(run.title) + indexHeader(run) + "<section>\n";
    h += deviceNotes(run);
    h += run.scenes.empty() ? "<p class=\"muted\">No scenes were run.</p>\n"
                            : scenesTable(run) + allMetricsTable(run);
    h += "</section>\n</main>\n";
    return h + pageFooter(run.createdAt, run.commandLine);
}

}  // namespace twinrender::report
