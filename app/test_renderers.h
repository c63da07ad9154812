// Several renderers measured against one reference in one run (`run --test realtime --test
// external`, docs/cli.md): each renders every scene, is compared with the same reference and
// held to the same bounds, and the scene's report holds them side by side
// (report::SceneReport::tests).
#pragma once

#include <string>
#include <vector>

#include "report/report.h"

namespace twinrender::app {

// A test renderer as `--test` names it: "realtime", "external", "images" (--test-images), or the
// built-in one with settings of its own, "realtime:KEY=VALUE[,KEY=VALUE...]" (realtime.* keys,
// applied after the run's --set), so that two of its methods stand side by side.
struct TestRendererSpec {
    std::string name;                    // as given: the report's name for it
    std::string renderer;                // makeRenderer's name: "realtime", "external", "images"
    std::vector<std::string> overrides;  // its own KEY=VALUE settings
};

// Throws core::InputError for another renderer, settings on another than the built-in one, or
// a key outside realtime.* (every test renderer is measured against the same reference).
TestRendererSpec parseTestRenderer(const std::string& spec);

// The folder of the k-th test renderer's files, relative to the scene's: the first renderer's
// are the scene folder's own (""), the others' in "tests/<name>/" (a character of the name that
// is not a letter, a digit, '.', '-' or '_' as '_').
std::string testRendererFolder(const std::vector<std::string>& names, std::size_t k);

// One scene's report from each test renderer's (in `names` order, one each): the first
// renderer's report with every renderer's results in `tests` and the other renderers' checks that
// did not pass, and their errors, added to its checks as "<name>:<metric>" ("<name>:render").
// With one renderer, its report as it is.
report::SceneReport joinTestRenderers(std::vector<report::SceneReport> reports,
                                      const std::vector<std::string>& names);

}  // namespace twinrender::app
