// Where tests write their files: a folder of the build tree (TWINRENDER_TEST_SCRATCH, set for
// every test binary), so that test runs of two build trees never share a folder.
#pragma once

#include <filesystem>
#include <string>

namespace twinrender::testing {

// An empty folder `name` in the build tree's scratch folder, made afresh.
inline std::filesystem::path freshDir(const std::string& name) {
    const auto dir = std::filesystem::path(TWINRENDER_TEST_SCRATCH) / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// A path for the file `name` in the scratch folder (the folder exists).
inline std::filesystem::path scratchFile(const std::string& name) {
    const auto dir = std::filesystem::path(TWINRENDER_TEST_SCRATCH);
    std::filesystem::create_directories(dir);
    return dir / name;
}

}  // namespace twinrender::testing
