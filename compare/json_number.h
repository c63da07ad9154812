// Numbers in the JSON files twinrender writes. JSON has no infinity or NaN (an identical pair
// has PSNR = +inf, a metric over an empty mask is NaN): such values are written as the
// strings "Infinity", "-Infinity" and "NaN", and read back.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace twinrender::compare {

// A number, or "Infinity", "-Infinity", "NaN" for the values JSON cannot hold.
nlohmann::json jsonNumber(double value);
// A number or one of those strings; nullopt for anything else.
std::optional<double> numberFromJson(const nlohmann::json& value);
// {key: jsonNumber(value)} of a map of numbers (metrics, timings, counters).
nlohmann::json numbersJson(const std::map<std::string, double>& numbers);

}  // namespace twinrender::compare
