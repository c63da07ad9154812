// What the fuzz targets share (CONTRIBUTING.md, "Fuzzing"): each target is the body of
// LLVMFuzzerTestOneInput, linked either with libFuzzer (scripts/fuzz, clang) or with
// replay_main.cpp, which feeds it the files of fuzz/regressions/ and fuzz/corpus/ under ctest.
// The readers take paths, so an input goes through a file, as a user's would.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace twinrender::fuzz {

// A folder of this process's own under the temp dir, created on first use and removed at exit.
const std::filesystem::path& scratchDir();

// Writes `bytes` to scratchDir() / name and returns the path.
std::filesystem::path writeScratchFile(const std::string& name, std::string_view bytes);

// The input as text.
inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

// The parts of `text` between lines that hold only "%%" (a target's several inputs in one).
std::vector<std::string> splitParts(std::string_view text);

// Runs `body`. Bad input is an expected answer (the command line's exit 4 or 3): InputError
// and NotComparableError are swallowed. Any other exception escapes and ends the process, as
// a crash: the commands would report it as an unclear error.
void expectCleanOutcome(const std::function<void()>& body);

}  // namespace twinrender::fuzz
