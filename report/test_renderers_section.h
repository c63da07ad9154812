// The scene page's section for a run that measures several renderers against one reference
// (`run --test A --test B`, report.h's SceneReport::tests): one table, a column per renderer,
// its beauty above its metrics, each value coloured by that renderer's own checks.
#pragma once

#include <string>

#include "report/report.h"

namespace twinrender::report {

// The section's HTML; "" for a scene measured with one renderer.
std::string testRenderersSection(const SceneReport& scene);

}  // namespace twinrender::report
