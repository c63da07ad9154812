#include "report/html_page.h"

#include <fmt/format.h>

#include <stdexcept>

#include "compare/metric_table.h"
#include "report/markup.h"
#include "report/report_assets.h"

namespace twinrender::report {

using compare::formatValue;
using compare::metricDescription;
using compare::metricUnit;
using compare::MetricValues;
using compare::Status;
using compare::toString;

namespace {

std::string asset(std::string_view name) {
    auto text = findReportAsset(name);
    if (!text) throw std::logic_error(fmt::format("report asset '{}' is not embedded", name));
    return std::string(*text);
}

// Inline <script> text must not contain "</" (it would end the element early).
std::string scriptSafe(std::string text) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/')
            out += "<\\";
        else
            out += text[i];
    }
    return out;
}

}  // namespace

std::string pageHead(const std::string& title) {
    // The policy allows inline style and script and local images and videos only: any reference to
    // the network is blocked (and reported by the self-test), so the report provably works offline.
    return fmt::format(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
        "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; "
        "img-src 'self' file: data:; media-src 'self' file:; style-src 'unsafe-inline'; script-src "
        "'unsafe-inline'\">\n"
        "<title>{}</title>\n<link rel=\"icon\" href=\"data:,\">\n<script>\n{}</script>\n"
        "<style>\n{}</style>\n</head>\n<body>\n",
        htmlEscape(title), scriptSafe(asset("selftest.js")), asset("report.css"));
}

std::string pageHeader(const std::string& title, std::optional<Status> verdict,
                       const std::vector<std::string>& facts, const std::string& backLink) {
    std::string h = "<header class=\"top\">\n";
    if (!backLink.empty()) h += backLink + "\n";
    h += "<h1>" + htmlEscape(title) + "</h1>";
    if (verdict) {
        h += ' ';  // appended apart: " " + temporary trips GCC 12's -Wrestrict false positive
        h += badge(*verdict);
    }
    h += "\n<div class=\"facts\">";
    for (const std::string& fact : facts) h += "<span>" + fact + "</span>";
    return h + "</div>\n</header>\n<main>\n";
}

std::string pageFooter(const std::string& createdAt, const std::string& commandLine,
                       const std::string& script, const std::string& data) {
    std::string f = "<footer>\n";
    f += "<div>Made by <b>twinrender</b>";
    if (!createdAt.empty()) f += " on " + htmlEscape(createdAt);
    f += ".";
    if (!commandLine.empty()) f += " Reproduce with <code>" + htmlEscape(commandLine) + "</code>.";
    f +=
        "</div>\n<pre id=\"selftest\" data-status=\"pending\">selftest: pending</pre>\n</footer>\n";
    if (!data.empty())
        f += "<script type=\"application/json\" id=\"buffers\">" + scriptSafe(data) + "</script>\n";
    f += "<script>\n" + scriptSafe(asset(script)) + "</script>\n</body>\n</html>\n";
    return f;
}

std::string reportPage(const std::string& title, const std::string& body,
                       const std::string& createdAt, const std::string& commandLine) {
    return pageHead(title) + body + pageFooter(createdAt, commandLine);
}

std::string badge(Status status) {
    return fmt::format("<span class=\"badge {0}\">{0}</span>", toString(status));
}

std::string metricTitle(const std::string& metric) {
    const std::string description = metricDescription(metric);
    return description.empty() ? "" : " title=\"" + htmlEscape(description) + "\"";
}

std::string metricHeaderCell(const std::string& metric) {
    const std::string unit = metricUnit(metric);
    return "<th class=\"num\"" + metricTitle(metric) + "><span class=\"mono\">" +
           htmlEscape(metric) + "</span>" +
           (unit.empty() ? "" : " <span class=\"unit\">" + htmlEscape(unit) + "</span>") + "</th>";
}

std::string metricValueCell(const MetricValues& metrics, const std::string& metric,
                            bool highlighted, std::optional<Status> status) {
    const auto it = metrics.find(metric);
    // A check's status, else the chart column's mark (pass-coloured).
    const std::string_view mark = status ? toString(*status) : highlighted ? "pass" : "";
    return fmt::format("<td class=\"num{}{}\">", mark.empty() ? "" : " ", mark) +
           (it == metrics.end() ? std::string("—") : htmlEscape(formatValue(it->second))) + "</td>";
}

std::string errorRow(std::size_t columns, const std::string& error) {
    return fmt::format(
        "<tr class=\"problems\"><td></td><td colspan=\"{}\"><ul><li "
        "class=\"fail\">{}</li></ul></td></tr>\n",
        columns, htmlEscape(error));
}

}  // namespace twinrender::report
