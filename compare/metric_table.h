// Metric keys and their properties (DESIGN.md, "Metric names").
#pragma once

#include <string>
#include <string_view>

namespace twinrender::compare {

// Unit of a metric for tables ("dB", "°", "px", "ms"; "" for ratios and fractions).
std::string metricUnit(std::string_view metric);

}  // namespace twinrender::compare
