// Where tests write their files: a folder of the build tree named after the test binary
// (BUILD/test_scratch/<binary>), so that test runs of two build trees, or of two binaries,
// never share a folder. The build tree and the source folder are found at run time
// (core/install_layout.h), so no compile line names a folder of one clone.
#pragma once

#include <filesystem>
#include <string>

#include "core/install_layout.h"

namespace twinrender::testing {

// The source folder this build was configured from.
inline std::filesystem::path sourceDir() {
    return core::sourceDir();
}

// The twinrender program of this build tree.
inline std::string twinrenderProgram() {
    return (core::buildDir() / "app" / "twinrender").string();
}

// This test binary's scratch folder (it may not exist yet).
inline std::filesystem::path scratchRoot() {
    return core::buildDir() / "test_scratch" /
           std::filesystem::read_symlink("/proc/self/exe").filename();
}

// An empty folder `name` in the build tree's scratch folder, made afresh.
inline std::filesystem::path freshDir(const std::string& name) {
    const auto dir = scratchRoot() / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// A path for the file `name` in the scratch folder (the folder exists).
inline std::filesystem::path scratchFile(const std::string& name) {
    const auto dir = scratchRoot();
    std::filesystem::create_directories(dir);
    return dir / name;
}

}  // namespace twinrender::testing
