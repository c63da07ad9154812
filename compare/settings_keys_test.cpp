#include "compare/settings_keys.h"

#include <gtest/gtest.h>

namespace twinrender::compare {
namespace {

using nlohmann::json;

std::vector<std::string> keysOf(const json& settings) {
    std::vector<std::string> keys;
    for (const auto& [k, v] : flattenSettings(settings)) keys.push_back(k);
    return keys;
}

TEST(SettingsKeys, RecordedFullKeysAreNotPrefixedAgain) {
    const json run = {
        {"scene_file", "scenes/planet.toml"},
        {"realtime", {{"realtime.ssss.radius_scale", 0.6}, {"realtime.depth", "log"}}},
        {"raymarch", {{"raymarch.spp", 1}}}};
    EXPECT_EQ(keysOf(run), (std::vector<std::string>{"raymarch.spp", "realtime.depth",
                                                     "realtime.ssss.radius_scale", "scene_file"}));
    const auto flat = flattenSettings(run);
    EXPECT_EQ(flat[2].second, 0.6);
}

TEST(SettingsKeys, NestedObjectsJoinWithDots) {
    EXPECT_EQ(keysOf(json{{"realtime", {{"ssss", {{"enabled", true}}}}}, {"varied", {{"a.b", 1}}}}),
              (std::vector<std::string>{"realtime.ssss.enabled", "varied.a.b"}));
    // "realtimex" does not start with "realtime.": it is joined.
    EXPECT_EQ(keysOf(json{{"realtime", {{"realtimex", 1}}}}),
              std::vector<std::string>{"realtime.realtimex"});
}

TEST(SettingsKeys, LeavesAtTheTopHaveNoKey) {
    EXPECT_EQ(keysOf(json(3)), std::vector<std::string>{""});
    EXPECT_EQ(keysOf(json::object()), std::vector<std::string>{""});
    EXPECT_EQ(keysOf(json{{"a", json::object()}}), std::vector<std::string>{"a"});
}

}  // namespace
}  // namespace twinrender::compare
