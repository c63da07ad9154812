#include "core/oiio_module.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include "core/error.h"
#include "core/install_layout.h"

namespace twinrender::core::oiio {

namespace {

const Api& load() {
    // Beside the program, as installed or built (install_layout.h).
    const std::string path = oiioModulePath().string();
    // RTLD_LOCAL: OpenImageIO's symbols stay out of the program's way; the module is never
    // unloaded.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle)
        throw InputError(fmt::format(
            "cannot load the OpenImageIO module {} ({}), which reads and writes every image "
            "other than PNG; rebuild twinrender (cmake --build) or reinstall it, and check that "
            "OpenImageIO is installed (scripts/setup)",
            path, dlerror()));
    auto entry = reinterpret_cast<EntryPoint>(dlsym(handle, ENTRY_POINT));
    if (!entry)
        throw InputError(
            fmt::format("{}: the OpenImageIO module has no entry point {}; rebuild "
                        "twinrender (cmake --build)",
                        path, ENTRY_POINT));
    return *entry();
}

}  // namespace

const Api& api() {
    static const Api& loaded = load();
    return loaded;
}

}  // namespace twinrender::core::oiio
