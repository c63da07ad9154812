#include "compare/settings_keys.h"

namespace twinrender::compare {

namespace {

std::string join(const std::string& prefix, const std::string& key) {
    if (prefix.empty() || key.rfind(prefix + ".", 0) == 0) return key;
    return prefix + "." + key;
}

void flatten(const nlohmann::json& j, const std::string& prefix,
             std::vector<std::pair<std::string, nlohmann::json>>& out) {
    if (j.is_object() && !j.empty()) {
        for (const auto& [k, v] : j.items()) flatten(v, join(prefix, k), out);
        return;
    }
    out.emplace_back(prefix, j);
}

}  // namespace

std::vector<std::pair<std::string, nlohmann::json>> flattenSettings(
    const nlohmann::json& settings) {
    std::vector<std::pair<std::string, nlohmann::json>> out;
    flatten(settings, "", out);
    return out;
}

}  // namespace twinrender::compare
