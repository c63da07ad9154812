#include "report/csv.h"

#include "compare/thresholds.h"

namespace twinrender::report {

using compare::exactValue;

std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
    std::string out = "\"";
    for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string csvNumber(const std::map<std::string, double>& numbers, const std::string& key) {
    const auto it = numbers.find(key);
    return it == numbers.end() ? "" : exactValue(it->second);
}

}  // namespace twinrender::report
