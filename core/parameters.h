// Settings read by string key in exactly one place per type (pbrt-v4's ParameterDictionary).
// A table holds the flattened keys of one TOML table ("ssss.enabled"), each with the place it
// came from ("scene.toml:12:1" or "--set"). Every getter marks its key as read;
// checkAllRead() turns any key nobody read into an InputError naming the file, line and key,
// so a typo never falls back to a default silently.
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace twinrender::core {

class ParameterTable {
  public:
    using Value = std::variant<bool, std::int64_t, double, std::string, std::vector<double>>;
    struct Entry {
        Value value;
        std::string where;  // "file:line:column", or "--set KEY=VALUE"
        mutable bool read = false;
        // The key as the --set override that gave the value wrote it
        // ("bodies.planet.particles"); empty: the prefixed key ("bodies[0].particles").
        std::string shownKey;
    };

    ParameterTable() = default;
    // `prefix` is prepended to keys in messages ("realtime", "bodies[planet]").
    ParameterTable(std::string prefix, std::string file);

    void set(const std::string& key, Value value, std::string where, std::string shownKey = {});
    bool has(std::string_view key) const;
    // Marks every key under `prefix` ("compare.thresholds") as read and returns their names.
    std::vector<std::string> keysUnder(std::string_view prefix) const;
    const std::string& prefix() const { return mPrefix; }
    const std::string& file() const { return mFile; }
    // "file:line:column: key 'prefix.key'" for messages ("--set KEY=VALUE: key 'KEY'" for a
    // value from an override).
    std::string describe(std::string_view key) const;

    bool getBool(std::string_view key, bool fallback) const;
    // Integers; [min, max] is checked and a value outside is an error naming the key.
    std::int64_t getInt(std::string_view key, std::int64_t fallback, std::int64_t min,
                        std::int64_t max) const;
    // Numbers (integers accepted); [min, max] checked, NaN rejected.
    double getDouble(std::string_view key, double fallback, double min, double max) const;
    std::string getString(std::string_view key, std::string fallback) const;
    // A string that must be one of `allowed`.
    std::string getEnum(std::string_view key, std::string fallback,
                        std::initializer_list<std::string_view> allowed) const;
    glm::dvec3 getVec3(std::string_view key, glm::dvec3 fallback) const;
    // Present-or-not forms; a present key of the wrong type is an error.
    std::optional<double> findDouble(std::string_view key) const;
    std::optional<std::string> findString(std::string_view key) const;
    std::optional<glm::dvec3> findVec3(std::string_view key) const;
    // The raw entry (marks it read), or nullptr.
    const Entry* find(std::string_view key) const;
    // A required key: throws naming the key when absent.
    const Entry& require(std::string_view key) const;

    // Throws InputError for the first key never read ("unknown key").
    void checkAllRead() const;
    const std::map<std::string, Entry, std::less<>>& entries() const { return mEntries; }

  private:
    // The key as messages name it: as its override wrote it, else prefixed.
    std::string shownKey(std::string_view key) const;
    [[noreturn]] void typeError(std::string_view key, std::string_view expected) const;

    std::string mPrefix;
    std::string mFile;
    std::map<std::string, Entry, std::less<>> mEntries;
};

// Human-readable form of a value, for messages and the settings JSON.
std::string toString(const ParameterTable::Value& value);

}  // namespace twinrender::core
