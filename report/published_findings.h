// The findings of the full studies as the docs publish them: docs/findings.json, written by
// scripts/record-findings when a doc script (scripts/studies-doc, scripts/methods-doc) runs the
// full studies, and compiled in. The studies page puts a quick run's finding beside the
// published one, so that a reader sees which figures a quick run moves.
//
// docs/findings.json:
//   {"format": "twinrender-published-findings", "version": 1,
//    "studies": {"<study>": {"finding", "page", ["points"], ["measured"]}}}
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace twinrender::report {

struct PublishedFinding {
    std::string finding;   // the full run's one-line finding, as the study printed it
    std::string page;      // the docs page that shows it, "docs/light.md"
    std::string measured;  // the day of the full run, "2026-11-28"; "" when not recorded
};

// The published finding of `study`, or nullopt for a study the docs do not publish.
std::optional<PublishedFinding> publishedFinding(std::string_view study);

}  // namespace twinrender::report
