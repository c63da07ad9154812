#include "report/published_findings.h"

#include <nlohmann/json.hpp>
#include <span>
#include <stdexcept>

#include "core/embedded_file.h"

namespace twinrender::report {

// docs/findings.json, compiled in (report/CMakeLists.txt).
std::span<const core::EmbeddedFile> publishedFindingFiles();

namespace {

const nlohmann::json& findings() {
    // Parsed once; the file is part of the build, so a malformed one is the build's fault.
    static const nlohmann::json all = [] {
        const auto text = core::findEmbeddedFile(publishedFindingFiles(), "findings.json");
        if (!text) throw std::logic_error("docs/findings.json is not compiled in");
        nlohmann::json j = nlohmann::json::parse(*text);
        if (j.value("format", "") != "twinrender-published-findings" || !j.contains("studies"))
            throw std::logic_error("docs/findings.json is not a twinrender-published-findings");
        return j;
    }();
    return all;
}

}  // namespace

std::optional<PublishedFinding> publishedFinding(std::string_view study) {
    const nlohmann::json& studies = findings().at("studies");
    const auto it = studies.find(study);
    if (it == studies.end()) return std::nullopt;
    return PublishedFinding{it->at("finding").get<std::string>(), it->at("page").get<std::string>(),
                            it->value("measured", "")};
}

}  // namespace twinrender::report
