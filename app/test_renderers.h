// Several renderers measured against one reference in one run (`run --test realtime --test
// external`, docs/cli.md): each renders every scene, is compared with the same reference and
// held to the same bounds, and the scene's report holds them side by side
// (report::SceneReport::tests).
#pragma once

#include <string>
#include <vector>

#include "report/report.h"

namespace twinrender::app {

// The folder of the k-th test renderer's files, relative to the scene's: the first renderer's
// are the scene folder's own (""), the others' in "tests/<name>/".
std::string testRendererFolder(const std::vector<std::string>& names, std::size_t k);

// One scene's report from each test renderer's (in `names` order, one each): the first
// renderer's report with every renderer's results in `tests` and the other renderers' checks that
// did not pass, and their errors, added to its checks as "<name>:<metric>" ("<name>:render").
// With one renderer, its report as it is.
report::SceneReport joinTestRenderers(std::vector<report::SceneReport> reports,
                                      const std::vector<std::string>& names);

}  // namespace twinrender::app
