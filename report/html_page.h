// The scaffolding every HTML page of the report shares (the run's index and scene pages, the
// sweep's and the studies' pages): the head with the inline style sheet and the self-test,
// the header with the title and a row of facts, the footer with how to reproduce the page,
// and the table cells the pages have in common.
//
// Every page carries a self-test: it records script errors, console.error calls and images
// that fail to load into <pre id="selftest">, which reads "selftest: ok" once the page has
// loaded without any, or "selftest: FAIL" and one line per problem
// (tests/report_browser_test.cpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "compare/thresholds.h"

namespace twinrender::report {

using compare::MetricValues;
using compare::Status;

// From <!DOCTYPE html> to the opening <body>: the title, a content security policy that
// blocks any network access, the self-test script and the style sheet.
std::string pageHead(const std::string& title);

// <header class="top">: an optional link back (HTML), the title and the verdict's badge, and
// the facts, each HTML that goes into a <span>; then <main> opens.
std::string pageHeader(const std::string& title, std::optional<Status> verdict,
                       const std::vector<std::string>& facts, const std::string& backLink = "");

// The footer with `createdAt` and `commandLine` (either may be empty) and the self-test's
// output, then `data` as the JSON <script id="buffers"> (none when empty), the page's script
// (a report asset: "index.js", "scene.js"), and the end of the page.
std::string pageFooter(const std::string& createdAt, const std::string& commandLine,
                       const std::string& script = "index.js", const std::string& data = "");

// A whole page: head, `body` (everything inside <body> above the footer, e.g. pageHeader()
// and the sections of <main>, closed), and footer.
std::string reportPage(const std::string& title, const std::string& body,
                       const std::string& createdAt, const std::string& commandLine);

// <span class="badge pass">pass</span>
std::string badge(Status status);

// ` title="..."`: the metric's meaning and better direction as a tooltip; "" for an unknown
// metric.
std::string metricTitle(const std::string& metric);

// A table's column header of a metric: its key and its unit, its meaning as the tooltip.
std::string metricHeaderCell(const std::string& metric);

// A table cell of a metric's value, "—" when the map lacks it; `highlighted` marks the
// column of the page's chart. A `status` (the metric's checks) colours the cell instead.
std::string metricValueCell(const MetricValues& metrics, const std::string& metric,
                            bool highlighted, std::optional<Status> status = std::nullopt);

// The row under a table row that failed: the error across `columns` columns, after one
// empty cell.
std::string errorRow(std::size_t columns, const std::string& error);

}  // namespace twinrender::report
