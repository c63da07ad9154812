#include "core/parameters.h"

#include <fmt/format.h>

#include <cmath>

#include "core/error.h"

namespace twinrender::core {

ParameterTable::ParameterTable(std::string prefix, std::string file)
    : mPrefix(std::move(prefix)), mFile(std::move(file)) {}

void ParameterTable::set(const std::string& key, Value value, std::string where,
                         std::string shownKey) {
    mEntries[key] = Entry{std::move(value), std::move(where), false, std::move(shownKey)};
}

bool ParameterTable::has(std::string_view key) const {
    return mEntries.find(key) != mEntries.end();
}

std::vector<std::string> ParameterTable::keysUnder(std::string_view prefix) const {
    std::vector<std::string> out;
    const std::string dotted = std::string(prefix) + ".";
    for (const auto& [k, e] : mEntries)
        if (k.rfind(dotted, 0) == 0) {
            e.read = true;
            out.push_back(k);
        }
    return out;
}

std::string ParameterTable::shownKey(std::string_view key) const {
    auto it = mEntries.find(key);
    if (it != mEntries.end() && !it->second.shownKey.empty()) return it->second.shownKey;
    return mPrefix.empty() ? std::string(key) : mPrefix + "." + std::string(key);
}

std::string ParameterTable::describe(std::string_view key) const {
    auto it = mEntries.find(key);
    const std::string& where = it != mEntries.end() ? it->second.where : mFile;
    return fmt::format("{}: key '{}'", where.empty() ? mFile : where, shownKey(key));
}

const ParameterTable::Entry* ParameterTable::find(std::string_view key) const {
    auto it = mEntries.find(key);
    if (it == mEntries.end()) return nullptr;
    it->second.read = true;
    return &it->second;
}

const ParameterTable::Entry& ParameterTable::require(std::string_view key) const {
    const Entry* e = find(key);
    if (!e)
        throw InputError(
            fmt::format("{}: required key '{}' is missing; add it", mFile,
                        mPrefix.empty() ? std::string(key) : mPrefix + "." + std::string(key)));
    return *e;
}

void ParameterTable::typeError(std::string_view key, std::string_view expected) const {
    auto it = mEntries.find(key);
    throw InputError(fmt::format("{} has the wrong type: expected {}, got {}", describe(key),
                                 expected, it != mEntries.end() ? toString(it->second.value) : ""));
}

namespace {
template <typename... Args>
[[noreturn]] void rangeError(const ParameterTable& t, std::string_view key, std::string_view range,
                             const std::string& got) {
    throw InputError(
        fmt::format("{} is out of range: {} (allowed: {})", t.describe(key), got, range));
}
}  // namespace

bool ParameterTable::getBool(std::string_view key, bool fallback) const {
    const Entry* e = find(key);
    if (!e) return fallback;
    if (auto* b = std::get_if<bool>(&e->value)) return *b;
    typeError(key, "true or false");
}

std::int64_t ParameterTable::getInt(std::string_view key, std::int64_t fallback, std::int64_t min,
                                    std::int64_t max) const {
    const Entry* e = find(key);
    if (!e) return fallback;
    std::int64_t v;
    if (auto* i = std::get_if<std::int64_t>(&e->value))
        v = *i;
    else if (auto* d = std::get_if<double>(&e->value);
             d && std::floor(*d) == *d && std::abs(*d) < 9e15)
        v = static_cast<std::int64_t>(*d);
    else
        typeError(key, "an integer");
    if (v < min || v > max)
        rangeError(*this, key, fmt::format("{}..{}", min, max), std::to_string(v));
    return v;
}

double ParameterTable::getDouble(std::string_view key, double fallback, double min,
                                 double max) const {
    auto v = findDouble(key);
    if (!v) return fallback;
    if (!(*v >= min && *v <= max))
        rangeError(*this, key, fmt::format("{}..{}", min, max), fmt::format("{}", *v));
    return *v;
}

std::optional<double> ParameterTable::findDouble(std::string_view key) const {
    const Entry* e = find(key);
    if (!e) return std::nullopt;
    if (auto* d = std::get_if<double>(&e->value)) return *d;
    if (auto* i = std::get_if<std::int64_t>(&e->value)) return static_cast<double>(*i);
    typeError(key, "a number");
}

std::string ParameterTable::getString(std::string_view key, std::string fallback) const {
    auto v = findString(key);
    return v ? *v : fallback;
}

std::optional<std::string> ParameterTable::findString(std::string_view key) const {
    const Entry* e = find(key);
    if (!e) return std::nullopt;
    if (auto* s = std::get_if<std::string>(&e->value)) return *s;
    typeError(key, "a string");
}

std::string ParameterTable::getEnum(std::string_view key, std::string fallback,
                                    std::initializer_list<std::string_view> allowed) const {
    std::string v = getString(key, fallback);
    for (auto a : allowed)
        if (a == v) return v;
    std::string list;
    for (auto a : allowed) list += (list.empty() ? "" : " | ") + std::string(a);
    rangeError(*this, key, list, "\"" + v + "\"");
}

glm::dvec3 ParameterTable::getVec3(std::string_view key, glm::dvec3 fallback) const {
    auto v = findVec3(key);
    return v ? *v : fallback;
}

std::optional<glm::dvec3> ParameterTable::findVec3(std::string_view key) const {
    const Entry* e = find(key);
    if (!e) return std::nullopt;
    auto* a = std::get_if<std::vector<double>>(&e->value);
    if (!a || a->size() != 3) typeError(key, "an array of three numbers");
    for (double x : *a)
        if (!std::isfinite(x)) rangeError(*this, key, "finite numbers", toString(e->value));
    return glm::dvec3((*a)[0], (*a)[1], (*a)[2]);
}

void ParameterTable::checkAllRead() const {
    for (const auto& [k, e] : mEntries)
        if (!e.read)
            throw InputError(
                fmt::format("{}: unknown key '{}'; check its spelling against "
                            "docs/scenes.md",
                            e.where, shownKey(k)));
}

std::string toString(const ParameterTable::Value& value) {
    return std::visit(
        [](const auto& v) -> std::string {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, bool>)
                return v ? "true" : "false";
            else if constexpr (std::is_same_v<T, std::string>)
                return "\"" + v + "\"";
            else if constexpr (std::is_same_v<T, std::vector<double>>) {
                std::string s = "[";
                for (std::size_t i = 0; i < v.size(); ++i)
                    s += (i ? ", " : "") + fmt::format("{}", v[i]);
                return s + "]";
            } else
                return fmt::format("{}", v);
        },
        value);
}

}  // namespace twinrender::core
