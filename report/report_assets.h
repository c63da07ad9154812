// The report's stylesheet and scripts: files in report/report_assets/, embedded at build time
// (cmake/embed_files.cmake) and inlined into every page, so a report needs no network and no
// files beside it but its images.
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "core/embedded_file.h"

namespace twinrender::report {

// Every embedded asset (defined in the generated embedded_reportAssetFiles.cpp).
std::span<const core::EmbeddedFile> reportAssetFiles();

// The text of an embedded file ("report.css", "selftest.js", "scene.js"), or nullopt.
inline std::optional<std::string_view> findReportAsset(std::string_view name) {
    return core::findEmbeddedFile(reportAssetFiles(), name);
}

}  // namespace twinrender::report
