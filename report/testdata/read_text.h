// A file's whole text, for the report tests to search.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace twinrender::report::testdata {

inline std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace twinrender::report::testdata
