#include "compare/report.h"

#include "compare/report_html.h"
#include "compare/report_json.h"
#include "compare/report_markdown.h"
#include "core/write_roots.h"

namespace twinrender::compare {

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

}  // namespace twinrender::compare
