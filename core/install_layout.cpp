#include "core/install_layout.h"

#include <fmt/format.h>

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

fs::path resourceDir() {
    // The paths from the program's folder are the install's (CMakeLists.txt).
    const fs::path installed =
        (programDir() / TWINRENDER_RESOURCES_FROM_PROGRAM).lexically_normal();
    if (fs::is_directory(installed / "scenes")) return installed;
    return TWINRENDER_SOURCE_DIR;
}

fs::path oiioModulePath() {
    return (programDir() / TWINRENDER_MODULES_FROM_PROGRAM / "twinrender_oiio.so")
        .lexically_normal();
}

}  // namespace twinrender::core
