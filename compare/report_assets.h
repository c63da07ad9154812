// The report's stylesheet and scripts: files in compare/report_assets/, embedded at build time
// (embed_report_assets.cmake) and inlined into every page, so a report needs no network and no
// files beside it but its images.
#pragma once

#include <optional>
#include <string_view>

namespace twinrender::compare {

// The text of an embedded file ("report.css", "selftest.js", "scene.js"), or nullopt.
std::optional<std::string_view> findReportAsset(std::string_view name);

}  // namespace twinrender::compare
