#include "report/test_renderers_section.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <set>

#include "compare/metric_table.h"
#include "report/html_page.h"
#include "report/markup.h"

namespace twinrender::report {

namespace {

// The worst of a renderer's checks of `metric`; none when it has none.
std::optional<Status> statusOf(const TestRendererReport& t, const std::string& metric) {
    std::optional<Status> st;
    for (const Check& c : t.checks)
        if (c.metric == metric) st = st ? compare::worst(*st, c.status) : c.status;
    return st;
}

std::string cell(const TestRendererReport& t, const std::string& metric) {
    if (std::find(t.notProvided.begin(), t.notProvided.end(), metric) != t.notProvided.end())
        return "<td class=\"num muted\">not provided</td>";
    return metricValueCell(t.metrics, metric, false, statusOf(t, metric));
}

}  // namespace

std::string testRenderersSection(const SceneReport& s) {
    if (s.tests.size() < 2) return "";
    std::string h =
        "<section>\n<h2>Test renderers</h2>\n<div class=\"scroll\"><table "
        "class=\"metrics\">\n<thead><tr><th>Metric</th>";
    for (const TestRendererReport& t : s.tests)
        h += "<th class=\"num\">" + htmlEscape(t.name) + "</th>";
    h += "</tr></thead>\n<tbody>\n<tr><td>beauty</td>";
    for (const TestRendererReport& t : s.tests) {
        const auto it = t.render.images.find("beauty");
        h += it == t.render.images.end()
                 ? "<td class=\"num muted\">—</td>"
                 : fmt::format("<td><img class=\"thumb\" src=\"{}\" alt=\"{} beauty\"></td>",
                               htmlEscape(urlPath(it->second)), htmlEscape(t.name));
    }
    h += "</tr>\n<tr><td>device</td>";
    for (const TestRendererReport& t : s.tests)
        h += "<td class=\"small\">" + htmlEscape(t.error.empty() ? t.render.device : t.error) +
             "</td>";
    h += "</tr>\n";
    std::set<std::string> keys;
    for (const TestRendererReport& t : s.tests) {
        for (const auto& [k, v] : t.metrics) keys.insert(k);
        keys.insert(t.notProvided.begin(), t.notProvided.end());
    }
    for (const std::string& m : compare::inMetricOrder({keys.begin(), keys.end()})) {
        h += fmt::format("<tr><td class=\"mono\"{}>{}</td>", metricTitle(m), htmlEscape(m));
        for (const TestRendererReport& t : s.tests) h += cell(t, m);
        h += "</tr>\n";
    }
    return h + "</tbody></table></div>\n</section>\n";
}

}  // namespace twinrender::report
