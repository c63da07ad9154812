// `twinrender merge`: joins the output folders of `run --shard K/N` or `sweep --shard K/N`
// (their manifests: app/shard.h) into the report one unsharded run writes, or those of
// `render --tiles K/N` or `run --tiles K/N` into the frames one render gives and, for a run,
// the run itself (app/reference_tiles.h). It reads the shards' and tiles' files only inside
// their folders: a manifest that names a scene, a combination or a tile folder outside its
// folder is exit 4. (A run's tiles' merge reads the scene files, thresholds and baseline the
// run was given, as the run does.)
#pragma once

#include <string>
#include <vector>

#include "app/exit_code.h"

namespace twinrender::app {

struct MergeOptions {
    std::vector<std::string> inputs;  // shard output folders
    std::string out;
    std::string commandLine;
    std::string annotations;  // for a run's shards: as RunOptions::annotations
};
// Checks that the shards belong together (same command, the same split, the same N, every K
// once, equal settings) and writes what one unsharded run writes. Returns the run's exit code (the
// worst verdict) or the sweep's (finishSweep, app/sweep_command.h).
ExitCode runMerge(const MergeOptions& options);

}  // namespace twinrender::app
