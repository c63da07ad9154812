#include "core/install_layout.h"

#include <fmt/format.h>

#include <fstream>
#include <string>
#include <system_error>

#include "core/error.h"

namespace twinrender::core {

namespace fs = std::filesystem;

fs::path programDir() {
    std::error_code error;
    const fs::path self = fs::read_symlink("/proc/self/exe", error);
    if (error)
        throw InputError(
            fmt::format("cannot find this program's own path (/proc/self/exe: {}), "
                        "from which it finds its scenes and image module",
                        error.message()));
    return self.parent_path();
}

namespace {

struct BuildTree {
    fs::path build, source;  // empty when the program is not in a build tree
};

// The first folder above the program holding CMakeCache.txt, and its CMAKE_HOME_DIRECTORY.
BuildTree findBuildTree() {
    BuildTree tree;
    for (fs::path dir = programDir(); !dir.empty(); dir = dir.parent_path()) {
        std::ifstream cache(dir / "CMakeCache.txt");
        if (cache) {
            const std::string key = "CMAKE_HOME_DIRECTORY:INTERNAL=";
            for (std::string line; std::getline(cache, line);)
                if (line.rfind(key, 0) == 0) return {dir, line.substr(key.size())};
        }
        if (dir == dir.parent_path()) break;
    }
    return tree;
}

const BuildTree& buildTree() {
    static const BuildTree tree = findBuildTree();
    return tree;
}

const BuildTree& requireBuildTree() {
    const BuildTree& tree = buildTree();
    if (tree.build.empty())
        throw InputError(fmt::format(
            "{}: this program is not in a build tree (no CMakeCache.txt above it, with its "
            "CMAKE_HOME_DIRECTORY), so it cannot find the source folder; run it from the build "
            "folder it was built in",
            programDir().string()));
    return tree;
}

}  // namespace

fs::path buildDir() {
    return requireBuildTree().build;
}

fs::path sourceDir() {
    return requireBuildTree().source;
}

fs::path resourceDir() {
    // The paths from the program's folder are the install's (CMakeLists.txt).
    const fs::path installed =
        (programDir() / TWINRENDER_RESOURCES_FROM_PROGRAM).lexically_normal();
    if (fs::is_directory(installed / "scenes") || buildTree().build.empty()) return installed;
    return buildTree().source;
}

fs::path oiioModulePath() {
    return (programDir() / TWINRENDER_MODULES_FROM_PROGRAM / "twinrender_oiio.so")
        .lexically_normal();
}

}  // namespace twinrender::core
