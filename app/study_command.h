// `twinrender study [NAME...]`: the stability studies of app/studies.h. Each study renders its
// points with the real-time renderer against a cached reference (app/reference_cache.h),
// measures every metric, and writes report/study_report.h's outputs with its finding.
#pragma once

#include <string>
#include <vector>

#include "app/exit_code.h"

namespace twinrender::app {

struct StudyOptions {
    std::vector<std::string> names;  // empty: every study
    std::string out = "out/studies";
    std::string cache;   // empty: OUT/reference_cache
    bool quick = false;  // fewer points and particles (tests, scripts/run)
    std::vector<std::string> sets;
    bool requireGpu = false;
    bool selfCheck = false;  // --self-check (app/per_set_check.h)
    double ppd = 67.0;
    std::string scenesDir;  // empty: scenes/studies of the working folder or the source tree
    std::string commandLine;
    // The report the studies belong to, relative to their page ("../index.html" under `run
    // --studies`), linked from it; "" for none.
    std::string back;
};
ExitCode runStudies(const StudyOptions& options);

}  // namespace twinrender::app
