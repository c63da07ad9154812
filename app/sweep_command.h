// `twinrender sweep`: speed against accuracy. The cartesian product of the varied settings,
// each combination rendered and timed (median of several frames) and compared with a
// reference that is rendered once per distinct reference and cached on disk by a hash of
// everything that affects it. Varying realtime.* keys measures the real-time renderer against
// the reference; varying raymarch.* keys measures the raymarcher against a tight render of
// itself (its convergence). Writes compare/sweep_report.h's outputs.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "app/exit_code.h"

namespace twinrender::app {

struct SweepOptions {
    std::string scene;
    std::vector<std::string> vary;  // "KEY=V1,V2,..." (repeatable)
    std::vector<std::string> sets;
    std::string out = "out/sweep";
    std::string cache;  // empty: OUT/reference_cache
    std::string metric = "beauty.flip";
    int frames = 0;  // frames per combination, 0: 5 for realtime, 1 for raymarch
    double ppd = 67.0;
    bool requireGpu = false;
    std::string shard;  // "K/N"; empty: all
    std::string commandLine;
};
ExitCode runSweep(const SweepOptions& options);

// "KEY=V1,V2,..." -> key and values. Commas inside [...] or quotes do not split (TOML arrays:
// camera.position=[0,-4,1],[0,-8,1]). Throws core::InputError naming the argument.
std::pair<std::string, std::vector<std::string>> parseVary(const std::string& text);

// The i-th combination of the product (the first key varies slowest): key=value overrides.
std::vector<std::string> combination(
    const std::vector<std::pair<std::string, std::vector<std::string>>>& vary, std::size_t index);

}  // namespace twinrender::app
