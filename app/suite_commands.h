// The commands that compare: `compare` (two images), `run` (the main job: every scene with
// both renderers, compared, reported) and `bless` (a run's metrics as the baseline).
// Each returns its verdict as an exit code (exit_code.h): pass, warn or fail.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "app/exit_code.h"
#include "app/render_job.h"
#include "compare/flip_pooling.h"
#include "report/report.h"

namespace twinrender::app {

struct CompareOptions {
    std::string reference;
    std::string test;
    std::string out = "out/compare";
    std::string thresholds;  // empty: no bounds, the verdict is pass
    // --scene: the scene the images show (its exposure and light); empty: exposure 1, no light
    std::string scene;
    std::vector<std::string> sets;                               // --set overrides of the scene
    double ppd = 67.0;                                           // ꟻLIP's pixels per degree
    double flipOver = compare::FlipPoolingSettings{}.overLevel;  // beauty.flip_over's level
};
ExitCode runCompare(const CompareOptions& options);

struct RunOptions {
    std::vector<std::string> inputs;  // scene files or folders of them; empty: scenes/
    std::string out = "out";
    std::string thresholds;  // empty: thresholds.toml beside the first input, if any
    std::string baseline;
    std::string junit;
    // Reference cache folder (app/reference_cache.h): given, every scene's reference comes
    // from it (shards on one disk can share it); empty, a sequence's references are cached in
    // OUT/reference_cache and a still scene's reference is rendered.
    std::string cache;
    std::vector<std::string> sets;
    bool requireGpu = false;
    double ppd = 67.0;
    double flipOver = compare::FlipPoolingSettings{}.overLevel;  // beauty.flip_over's level
    std::string commandLine;                                     // recorded in the report
    std::string shard;  // "K/N" (app/shard.h); empty: every scene
    // "K/N" (app/reference_tiles.h): part K of N of every reference, nothing compared; empty:
    // the whole run.
    std::string tiles;
    // Whether the report links to the stability studies in OUT/studies (main runs them after
    // the scenes: `run --studies`).
    bool linkStudies = false;
    std::string annotations;  // "github" | "none"; "": printAnnotations decides
    // --self-check: the per-set self-check on any device, not taken from the cache
    // (app/per_set_check.h).
    bool selfCheck = false;
    // --test: the renderers measured against the reference, each once: "realtime" (the
    // built-in one), "external" (`external`'s command, app/external_renderer.h) or "images"
    // (--test-images: the images in `external.images`, app/test_images.h). With several, the
    // first is the scene's own in the report and the others stand beside it
    // (app/test_renderers.h).
    std::vector<std::string> tests = {"realtime"};
    ExternalSettings external;
};
ExitCode runSuite(const RunOptions& options);

// The scene files a run renders: the files given, the .toml files of the folders given
// (sorted, without thresholds.toml), or the default suite's when none is given.
std::vector<std::filesystem::path> runSceneFiles(const RunOptions& options);

// Prints the run's checks that did not pass as CI annotations (report/annotations.h) in
// `format`: "github", "none", or "" for "github" when the environment has GITHUB_ACTIONS=true
// (as GitHub Actions sets it), else none. Paths are relative to GITHUB_WORKSPACE when set,
// else to the working folder.
void printAnnotations(const report::RunReport& run, const std::string& format);

// Writes the baseline of RUN_DIR (its summary.json) to `out` (default RUN_DIR/baseline.json).
ExitCode runBless(const std::string& runDir, const std::string& out);

}  // namespace twinrender::app
