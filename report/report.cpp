#include "report/report.h"

#include "core/write_roots.h"
#include "report/report_html.h"
#include "report/report_json.h"
#include "report/report_markdown.h"

namespace twinrender::report {

using compare::overallStatus;
using compare::Status;
using compare::worst;

namespace fs = std::filesystem;

Status SceneReport::status() const {
    if (!error.empty()) return Status::Fail;
    return overallStatus(checks);
}

Status RunReport::status() const {
    Status s = Status::Pass;
    for (const SceneReport& scene : scenes) s = worst(s, scene.status());
    return s;
}

void writeReport(const RunReport& run, const fs::path& dir) {
    core::makeFolders(dir);
    for (const SceneReport& s : run.scenes) writeMetricsJson(s, dir / s.name / "metrics.json");
    writeSummaryJson(run, dir / "summary.json");
    writeSummaryMarkdown(run, dir / "summary.md");
    writeHtmlReport(run, dir);
}

}  // namespace twinrender::report
