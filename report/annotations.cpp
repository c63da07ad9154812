#include "report/annotations.h"

#include <fmt/format.h>

#include <map>
#include <optional>

namespace twinrender::report {

using compare::Check;
using compare::Status;
using compare::worst;

namespace fs = std::filesystem;

namespace {

std::string escapeWorkflow(std::string_view text, bool property) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        if (c == '%')
            out += "%25";
        else if (c == '\r')
            out += "%0D";
        else if (c == '\n')
            out += "%0A";
        else if (property && c == ':')
            out += "%3A";
        else if (property && c == ',')
            out += "%2C";
        else
            out += c;
    }
    return out;
}

// The scene file as GitHub should see it: relative to root when it lies below it.
std::string annotatedPath(const std::string& file, const fs::path& root) {
    if (file.empty() || root.empty()) return file;
    const fs::path rel = fs::absolute(file).lexically_normal().lexically_relative(
        fs::absolute(root).lexically_normal());
    if (rel.empty() || *rel.begin() == "..") return file;
    return rel.generic_string();
}

// The line of a bound set in the scene file itself: `where` is "FILE:LINE:COLUMN" there.
std::optional<int> lineInSceneFile(const std::string& where, const std::string& sceneFile) {
    if (sceneFile.empty() || where.rfind(sceneFile + ":", 0) != 0) return std::nullopt;
    const std::string rest = where.substr(sceneFile.size() + 1);
    const auto colon = rest.find(':');
    const std::string digits = rest.substr(0, colon);
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos ||
        digits.size() > 9)
        return std::nullopt;
    return std::stoi(digits);
}

std::string sceneFileOf(const SceneReport& scene) {
    if (scene.settings.is_object() && scene.settings.contains("scene_file") &&
        scene.settings["scene_file"].is_string())
        return scene.settings["scene_file"].get<std::string>();
    return "";
}

std::string annotation(Status status, const std::string& file, std::optional<int> line,
                       const std::string& title, const std::string& message) {
    std::string properties;
    if (!file.empty()) properties += "file=" + escapeWorkflowProperty(file);
    if (line) properties += fmt::format("{}line={}", properties.empty() ? "" : ",", *line);
    properties += (properties.empty() ? "title=" : ",title=") + escapeWorkflowProperty(title);
    return fmt::format("::{} {}::{}\n", status == Status::Fail ? "error" : "warning", properties,
                       escapeWorkflowData(message));
}

}  // namespace

std::string escapeWorkflowData(std::string_view text) {
    return escapeWorkflow(text, false);
}

std::string escapeWorkflowProperty(std::string_view text) {
    return escapeWorkflow(text, true);
}

std::string githubAnnotations(const RunReport& run, const fs::path& root) {
    std::string out;
    for (const SceneReport& scene : run.scenes) {
        const std::string file = sceneFileOf(scene);
        const std::string shown = annotatedPath(file, root);
        if (!scene.error.empty()) {
            out +=
                annotation(Status::Fail, shown, std::nullopt,
                           "twinrender " + scene.name + ": not rendered or compared", scene.error);
            continue;
        }
        // A metric past its max is past its warn_max too: only its worst checks are said.
        std::map<std::string, Status> worstOf;
        for (const Check& c : scene.checks) worstOf[c.metric] = worst(worstOf[c.metric], c.status);
        for (const Check& c : scene.checks) {
            if (c.status == Status::Pass || c.status != worstOf[c.metric]) continue;
            out += annotation(c.status, shown, lineInSceneFile(c.where, file),
                              fmt::format("twinrender {}: {} {}", scene.name, c.metric,
                                          c.status == Status::Fail ? "failed" : "warned"),
                              c.message);
        }
    }
    return out;
}

}  // namespace twinrender::report
