// The run's HTML report: DIR/index.html (index_page.h), and DIR/<scene>/index.html, the scene
// page: its devices, links to its neighbours and raw files, the buffers of both renders side
// by side and as a swipe view, the error maps, the error split, every metric with its bounds
// and baseline ("n/a" where it does not apply), the stages that ran, devices and settings.
// Pages are html_page.h's, with its self-test.
#pragma once

#include <filesystem>

#include "report/report.h"

namespace twinrender::report {

// Writes DIR/index.html and DIR/<scene>/index.html for every scene (atomically). The images
// named in the reports must already be in place (the pages only link to them).
void writeHtmlReport(const RunReport& run, const std::filesystem::path& dir);

}  // namespace twinrender::report
