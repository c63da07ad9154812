// `twinrender sweep`: speed against accuracy. The cartesian product of the varied settings,
// each combination rendered and timed (median of several frames) and compared with a
// reference that is rendered once per distinct reference and cached on disk by a hash of
// everything that affects it. Varying realtime.* keys measures the real-time renderer against
// the reference; varying raymarch.* keys measures the raymarcher against a tight render of
// itself (its convergence). With thresholds, each combination is held to the scene's bounds
// as `run` holds a scene, and the cheapest that passes is named. On a sequence scene each
// combination renders every frame of the range, as `run` does (app/sequence_run.h), its row
// the summary over the frames and its time the median frame's. Writes
// report/sweep_report.h's outputs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/exit_code.h"
#include "app/render_job.h"
#include "compare/flip_pooling.h"
#include "report/sweep_report.h"

namespace twinrender::app {

struct SweepOptions {
    std::string scene;
    std::vector<std::string> vary;  // "KEY=V1,V2,..." (repeatable)
    std::vector<std::string> sets;
    std::string out = "out/sweep";
    std::string cache;  // empty: OUT/reference_cache
    std::string metric = "beauty.flip";
    std::string thresholds;  // thresholds file; empty: the combinations are not checked
    int frames = 0;          // frames per combination, 0: 5 for realtime, 1 for raymarch
    double ppd = 67.0;
    double flipOver = compare::FlipPoolingSettings{}.overLevel;  // beauty.flip_over's level
    bool requireGpu = false;
    bool selfCheck = false;  // --self-check (app/per_set_check.h)
    std::string shard;       // "K/N"; empty: all
    // "K/N" (app/reference_tiles.h): part K of N of every reference, nothing compared; empty:
    // the whole sweep.
    std::string tiles;
    std::string commandLine;
};
ExitCode runSweep(const SweepOptions& options);

// Every reference frame the sweep's combinations take, once per combination (and frame of a
// sequence): `visit` gets the scene it is rendered from (moved to the frame), the overrides
// its key is of, and the frame of a sequence. Checks the sweep's inputs as runSweep does.
void forEachSweepReference(
    const SweepOptions& options,
    const std::function<void(LoadedScene& scene, const std::vector<std::string>& overrides,
                             std::optional<std::int64_t> frame)>& visit);

// How a sweep ends, whole or merged from its shards: prints report::verdictLines and returns
// the exit code. Held to thresholds, the best combination's verdict (Pass when one passes);
// else Fail when a combination could not be rendered, and Pass otherwise.
ExitCode finishSweep(const report::SweepReport& report);

// "KEY=V1,V2,..." -> key and values. Commas inside [...] or quotes do not split (TOML arrays:
// camera.position=[0,-4,1],[0,-8,1]). Throws core::InputError naming the argument.
std::pair<std::string, std::vector<std::string>> parseVary(const std::string& text);

// The i-th combination of the product (the first key varies slowest): key=value overrides.
std::vector<std::string> combination(
    const std::vector<std::pair<std::string, std::vector<std::string>>>& vary, std::size_t index);

}  // namespace twinrender::app
