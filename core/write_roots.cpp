#include "core/write_roots.h"

#include <fmt/format.h>

#include <mutex>
#include <vector>

#include "core/error.h"

namespace twinrender::core {

namespace fs = std::filesystem;

namespace {

struct Roots {
    std::mutex mutex;
    std::vector<fs::path> folders;  // resolved (resolve())
};

Roots& roots() {
    static Roots r;
    return r;
}

// Absolute, with the symbolic links of its existing parts resolved and no "." or "..".
fs::path resolve(const fs::path& p) {
    std::error_code ec;
    fs::path r = fs::weakly_canonical(fs::absolute(p), ec);
    if (ec) r = fs::absolute(p).lexically_normal();
    // "a/b/" and "a/b" name one folder.
    if (!r.has_filename() && r.has_parent_path() && r != r.root_path()) r = r.parent_path();
    return r;
}

bool isPrefix(const fs::path& root, const fs::path& path) {
    auto r = root.begin(), p = path.begin();
    for (; r != root.end(); ++r, ++p)
        if (p == path.end() || *r != *p) return false;
    return true;
}

}  // namespace

void allowWritesUnder(const fs::path& dir) {
    std::lock_guard lock(roots().mutex);
    roots().folders.push_back(resolve(dir));
}

void clearWriteRoots() {
    std::lock_guard lock(roots().mutex);
    roots().folders.clear();
}

bool isInside(const fs::path& root, const fs::path& path) {
    return isPrefix(resolve(root), resolve(path));
}

void checkWriteAllowed(const fs::path& path) {
    std::lock_guard lock(roots().mutex);
    const std::vector<fs::path>& folders = roots().folders;
    if (folders.empty()) return;
    const fs::path p = resolve(path);
    for (const fs::path& r : folders)
        if (isPrefix(r, p)) return;
    std::string allowed;
    for (const fs::path& r : folders) allowed += (allowed.empty() ? "" : ", ") + r.string();
    throw OutputError(fmt::format(
        "{}: refusing to write outside the folders named on the command line ({}); a name in a "
        "scene, thresholds file, baseline or manifest led here",
        path.string(), allowed));
}

void makeFolders(const fs::path& dir) {
    checkWriteAllowed(dir);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
        throw OutputError(
            fmt::format("{}: cannot make the folder ({}); check that its parent is "
                        "writable and its disk not full",
                        dir.string(), ec.message()));
}

void requireInside(const fs::path& root, const fs::path& path, std::string_view what) {
    if (!isInside(root, path))
        throw InputError(
            fmt::format("{}: {} is outside {}; it may name only files inside the "
                        "folder it was given in",
                        what, path.string(), root.string()));
}

}  // namespace twinrender::core
