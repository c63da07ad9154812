// summary.md: a run's verdict in Markdown, to paste as a pull-request comment or to append to
// GitHub's job summary ($GITHUB_STEP_SUMMARY). A heading with the verdict, a line counting the
// scenes by status and naming the thresholds and baseline files, then one table row per scene:
// its status and, stacked in the cells (<br>), the metrics that failed or warned, their values,
// the bounds they crossed and, when the run had a baseline, their change from it. Scene and
// metric names link to the scene pages (DIR/<scene>/index.html#metric-<key>), relative to the
// report folder, where summary.md lies.
//
// Nothing in it depends on when or how the run was made (no times unless a time is checked, no
// command line), so the summary of merged shards equals that of one unsharded run.
#pragma once

#include <filesystem>
#include <string>

#include "report/report.h"

namespace twinrender::report {

std::string summaryMarkdown(const RunReport& run);

// Atomic write (temporary name, then rename).
void writeSummaryMarkdown(const RunReport& run, const std::filesystem::path& file);

}  // namespace twinrender::report
