// Fields of the CSV files of sweeps and studies (RFC 4180): one header line, one line per row.
#pragma once

#include <map>
#include <string>

namespace twinrender::report {

// The text as one field: quoted (with quotes doubled) when it holds a comma, a quote or a
// line break.
std::string csvField(const std::string& text);

// The number at full precision (exactValue: "nan", "inf", "-inf" for non-finite ones); empty
// when the map has no such key.
std::string csvNumber(const std::map<std::string, double>& numbers, const std::string& key);

}  // namespace twinrender::report
