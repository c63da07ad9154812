#include "app/output_folder.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "core/write_roots.h"

namespace twinrender::app {

namespace fs = std::filesystem;

namespace {

core::OutputError cannotWriteIn(const fs::path& dir, const std::string& why) {
    return core::OutputError(
        fmt::format("{}: cannot write in the output folder ({}); give another --out, or check "
                    "that it is writable and its disk not full",
                    dir.string(), why));
}

// A name in `dir` that no other process and no other call of this one uses.
fs::path uniqueName(const fs::path& dir, const char* what) {
    static std::atomic<unsigned> counter{0};
    return dir / fmt::format(".{}-{}-{}", what, getpid(), counter++);
}

void removeQuietly(const fs::path& path) {
    std::error_code ec;
    fs::remove_all(path, ec);
}

}  // namespace

void prepareOutputFolder(const fs::path& dir) {
    core::checkWriteAllowed(dir);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw cannotWriteIn(dir, ec.message());
    // A byte written and closed: a folder that refuses new files fails at open, a full disk
    // at write or close.
    const fs::path probe = uniqueName(dir, "write-probe");
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) throw cannotWriteIn(dir, std::strerror(errno));
    const bool written = ::write(fd, "x", 1) == 1;
    const int writeError = errno;
    const bool closed = ::close(fd) == 0;
    const int closeError = errno;
    ::unlink(probe.c_str());
    if (!written) throw cannotWriteIn(dir, std::strerror(writeError));
    if (!closed) throw cannotWriteIn(dir, std::strerror(closeError));
}

void writeTogether(const fs::path& dir, const std::function<void(const fs::path&)>& write) {
    prepareOutputFolder(dir);
    const fs::path staging = uniqueName(dir, "staging");
    try {
        fs::create_directory(staging);
        write(staging);
        // Every file is written: move them into place, folders first.
        std::vector<fs::path> files;
        for (const auto& e : fs::recursive_directory_iterator(staging)) {
            const fs::path target = dir / fs::relative(e.path(), staging);
            if (e.is_directory())
                fs::create_directories(target);
            else
                files.push_back(e.path());
        }
        for (const fs::path& f : files) fs::rename(f, dir / fs::relative(f, staging));
    } catch (const fs::filesystem_error& e) {
        removeQuietly(staging);
        throw cannotWriteIn(dir, fmt::format("{}: {}", e.path1().string(), e.code().message()));
    } catch (...) {
        removeQuietly(staging);
        throw;
    }
    removeQuietly(staging);
}

}  // namespace twinrender::app
