// A run's failures and warnings as GitHub Actions annotations: workflow commands that GitHub
// reads from a step's output and shows on the run's page and beside the pull request's files.
// One line per check that did not pass (of a metric's checks, the worst only: one past its max
// is past its warn_max too),
//
//     ::error file=scenes/planet.toml,title=twinrender planet%3A beauty.flip failed::beauty.flip
//     = 0.2 is above its max 0.15 (scenes/thresholds.toml:3:1)
//
// (::warning for a warning), naming the scene file, the metric, its value and the bound (the
// check's message); `line=` too when the bound was set in the scene file itself
// ([compare.thresholds]). A scene that could not be rendered or compared is one ::error with
// its error. GitLab and Jenkins read the JUnit XML instead (junit.h).
//
// Escaping as GitHub's toolkit does (@actions/core, command.ts): in the message % CR LF become
// %25 %0D %0A; in properties (file, title) also : and , become %3A and %2C.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "report/report.h"

namespace twinrender::report {

std::string escapeWorkflowData(std::string_view text);
std::string escapeWorkflowProperty(std::string_view text);

// The annotation lines of the run, each ending in '\n'; empty when every scene passed. A scene
// file (the scene's settings "scene_file") below `root` is named relative to it, as GitHub
// wants paths relative to the repository (GITHUB_WORKSPACE); others as they are.
std::string githubAnnotations(const RunReport& run, const std::filesystem::path& root);

}  // namespace twinrender::report
