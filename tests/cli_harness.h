// Runs the twinrender command as a user would and captures what it prints.
#pragma once

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>

#include "tests/scratch_dir.h"

namespace twinrender::test {

struct CommandResult {
    int exitCode = -1;
    std::string output;  // standard output and standard error together
};

// `environment`: "NAME=VALUE ..." set for this command only.
inline CommandResult runTwinrender(const std::string& args, const std::string& environment = "") {
    const std::string cmd =
        (environment.empty() ? "" : "env " + environment + " ") + std::string(TWINRENDER_BIN) + " " + args + " 2>&1";
    CommandResult r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf{};
    while (std::size_t n = std::fread(buf.data(), 1, buf.size(), pipe)) r.output.append(buf.data(), n);
    const int status = pclose(pipe);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

// A fresh folder for one test.
using twinrender::testing::freshDir;

inline void writeFile(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path) << text;
}

inline std::size_t countFiles(const std::filesystem::path& dir) {
    if (!std::filesystem::exists(dir)) return 0;
    std::size_t n = 0;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) n += e.is_regular_file();
    return n;
}

}  // namespace twinrender::test
