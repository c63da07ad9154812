// The run as JUnit XML, for CI systems that show test results.
#pragma once

#include <filesystem>
#include <string>

#include "report/report.h"

namespace twinrender::report {

// One <testsuite>, one <testcase> per scene and checked metric (classname "twinrender.SCENE",
// name METRIC) with the value and every bound as <property>; a <failure message=...> when a
// check fails, the warnings in <system-out>. A scene that could not be rendered is one
// testcase "render" with an <error>; a scene without checks one passing testcase "render".
std::string junitXml(const RunReport& run);

// Atomic write (temporary name, then rename).
void writeJunit(const RunReport& run, const std::filesystem::path& file);

}  // namespace twinrender::report
