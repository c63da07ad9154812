// `twinrender merge`: joins the output folders of `run --shard K/N` or `sweep --shard K/N`
// (their manifests: app/shard.h) into the report one unsharded run writes. It reads only
// inside the shards' folders: a manifest that names a scene or a combination folder outside
// its shard's folder is exit 4.
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
// Checks that the shards belong together (same command, the same N, every K once, equal
// settings) and writes what one unsharded run writes. Returns the run's exit code (the
// worst verdict) or the sweep's (finishSweep, app/sweep_command.h).
ExitCode runMerge(const MergeOptions& options);

}  // namespace twinrender::app
