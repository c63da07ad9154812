#include "fuzz/fuzz_support.h"

#include <fmt/format.h>
#include <unistd.h>

#include <fstream>
#include <system_error>

#include "core/error.h"

namespace twinrender::fuzz {
namespace fs = std::filesystem;

namespace {

struct ScratchDir {
    fs::path path;
    ScratchDir() {
        path = fs::temp_directory_path() / fmt::format("twinrender-fuzz-{}", getpid());
        fs::create_directories(path);
    }
    ~ScratchDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

}  // namespace

const fs::path& scratchDir() {
    static const ScratchDir dir;
    return dir.path;
}

fs::path writeScratchFile(const std::string& name, std::string_view bytes) {
    const fs::path path = scratchDir() / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
    return path;
}

std::vector<std::string> splitParts(std::string_view text) {
    std::vector<std::string> parts(1);
    std::size_t pos = 0;
    while (pos <= text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = text.substr(pos, end - pos);
        if (line == "%%")
            parts.emplace_back();
        else
            parts.back().append(line).append(end < text.size() ? "\n" : "");
        pos = end + 1;
    }
    return parts;
}

void expectCleanOutcome(const std::function<void()>& body) {
    try {
        body();
    } catch (const core::InputError&) {
    } catch (const core::NotComparableError&) {
    }
}

}  // namespace twinrender::fuzz
