// Runs the twinrender command as a user would and captures what it prints.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/scratch_dir.h"

namespace twinrender::test {

struct CommandResult {
    int exitCode = -1;
    std::string output;  // standard output and standard error together
};

// `environment`: "NAME=VALUE ..." set for this command only; `prefix`: a command that runs
// twinrender (with its arguments after it), e.g. one that limits what the process may do.
inline CommandResult runTwinrender(const std::string& args, const std::string& environment = "",
                                   const std::string& prefix = "") {
    const std::string cmd = (environment.empty() ? "" : "env " + environment + " ") + prefix +
                            ::twinrender::testing::twinrenderProgram() + " " + args + " 2>&1";
    CommandResult r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf{};
    while (std::size_t n = std::fread(buf.data(), 1, buf.size(), pipe))
        r.output.append(buf.data(), n);
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
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
        n += e.is_regular_file();
    return n;
}

inline std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// How often `what` occurs in `text` (overlapping occurrences too).
inline std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
}

// The parsed file, or a discarded value when it is not JSON.
inline nlohmann::json readJson(const std::filesystem::path& file) {
    std::ifstream in(file);
    return nlohmann::json::parse(in, nullptr, false);
}

// The first scene's numeric metrics of `twinrender run SCENE --out DIR/NAME --cache DIR/cache`
// with the --set overrides `sets` ("KEY=VALUE" each): the reference is rendered once per scene
// into DIR's cache. Empty, with a failure recorded, when the run wrote no summary.
inline std::map<std::string, double> runMetrics(const std::filesystem::path& scene,
                                                const std::filesystem::path& dir,
                                                const std::string& name,
                                                const std::vector<std::string>& sets) {
    const std::filesystem::path out = dir / name;
    std::string args =
        "run " + scene.string() + " --out " + out.string() + " --cache " + (dir / "cache").string();
    for (const std::string& s : sets) args += " --set " + s;
    const CommandResult r = runTwinrender(args);
    std::map<std::string, double> metrics;
    const nlohmann::json summary = readJson(out / "summary.json");
    if (r.exitCode == 4 || summary.is_discarded()) {
        ADD_FAILURE() << "twinrender " << args << ":\n" << r.output;
        return metrics;
    }
    for (const auto& [key, value] : summary["scenes"][0]["metrics"].items())
        if (value.is_number()) metrics[key] = value.get<double>();
    return metrics;
}

// The page's self-test verdict in headless Chromium in a window 1280 px wide (as
// tests/report_browser_test.cpp opens pages); empty when Chromium is not installed.
inline std::string selftestInBrowser(const std::filesystem::path& page,
                                     const std::filesystem::path& work) {
    const char* chromium = "/usr/bin/chromium";
    if (!std::filesystem::exists(chromium)) return "";
    const std::filesystem::path dom = work / "dom.html";
    const std::string cmd =
        std::string("timeout 120 ") + chromium +
        " --headless --no-sandbox --disable-gpu --no-first-run --disable-background-networking"
        " --hide-scrollbars --window-size=1280,900 --user-data-dir=" +
        (work / "profile").string() + " --virtual-time-budget=5000 --dump-dom 'file://" +
        page.string() + "' > " + dom.string() + " 2>/dev/null";
    if (std::system(cmd.c_str()) != 0) return "chromium failed";
    const std::string text = readText(dom);
    const auto at = text.find("id=\"selftest\"");
    if (at == std::string::npos) return "no selftest element";
    const auto start = text.find('>', at) + 1;
    return text.substr(start, text.find('<', start) - start);
}

}  // namespace twinrender::test
