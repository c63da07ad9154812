// The settings a render used, by the one name a user knows them by: the dotted key of the
// scene file and of --set (realtime.ssss.radius_scale), whatever the nesting of the JSON that
// records them. The scene page's settings table and the baseline's list of changed settings
// both name settings this way.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace twinrender::compare {

// Every leaf of `settings` with its dotted key, in the JSON's key order. Nested objects join
// their keys with dots, except where a member's key already starts with its parent's: a
// renderer's settings record full keys under the renderer's name ({"realtime":
// {"realtime.ssss.radius_scale": 0.6}}), which is the key realtime.ssss.radius_scale, not
// realtime.realtime.ssss.radius_scale. Empty objects are leaves; a leaf at the top (settings
// that are not an object, or an empty one) has the key "".
std::vector<std::pair<std::string, nlohmann::json>> flattenSettings(const nlohmann::json& settings);

}  // namespace twinrender::compare
