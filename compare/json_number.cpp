#include "compare/json_number.h"

#include <cmath>
#include <limits>

namespace twinrender::compare {

using nlohmann::json;

json jsonNumber(double value) {
    if (std::isnan(value)) return "NaN";
    if (std::isinf(value)) return value > 0 ? "Infinity" : "-Infinity";
    return value;
}

std::optional<double> numberFromJson(const json& value) {
    if (value.is_number()) return value.get<double>();
    if (value.is_string()) {
        const auto& s = value.get_ref<const std::string&>();
        if (s == "Infinity") return std::numeric_limits<double>::infinity();
        if (s == "-Infinity") return -std::numeric_limits<double>::infinity();
        if (s == "NaN") return std::numeric_limits<double>::quiet_NaN();
    }
    return std::nullopt;
}

json numbersJson(const std::map<std::string, double>& numbers) {
    json j = json::object();
    for (const auto& [k, v] : numbers) j[k] = jsonNumber(v);
    return j;
}

}  // namespace twinrender::compare
