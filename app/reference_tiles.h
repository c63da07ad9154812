// One reference frame split across machines (docs/cli.md, "Tiles"): `render --tiles K/N`,
// `run --tiles K/N` and `sweep --tiles K/N` render part K of N of each reference frame with the
// raymarcher (core/frame_part.h), and `twinrender merge` joins the N parts into the frames one
// render gives, bit for bit (core/part_join.h). A part's output folder carries a manifest,
// shard.json (app/shard.h), with "split": "tiles" and "references": [{"folder" (inside the
// part's folder, holding raymarch.exr and raymarch.json), "key" and "what"
// (app/reference_cache.h's key of the frame and what went into it), "scene", and "frame" for a
// sequence's frame}].
//
// A run's or a sweep's parts render no real-time frame and compare nothing: the merge joins
// the references into OUT/reference_cache and runs the command there, every reference a cache
// hit.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/exit_code.h"
#include "app/merge_command.h"
#include "app/render_job.h"
#include "app/suite_commands.h"
#include "app/sweep_command.h"
#include "core/frame_part.h"

namespace twinrender::app {

// "K/N" of --tiles; throws core::InputError naming the option.
core::FramePart parseTiles(const std::string& text);

// `command --tiles` with --shard (`shard`; `shardSplits`: what that splits) or --cache
// (`cache`) throws core::InputError naming both: a tile job renders its part of every reference.
void refuseTilesWith(const std::string& command, const std::string& shardSplits, bool shard,
                     bool cache);

// A command's reference frames: a walk calls `visit` with each one's scene (moved to the
// frame), the overrides its key is of (app/reference_cache.h) and, for a sequence, its frame.
using ReferenceVisit =
    std::function<void(LoadedScene& scene, const std::vector<std::string>& overrides,
                       std::optional<std::int64_t> frame)>;
using ReferenceWalk = std::function<void(const ReferenceVisit& visit)>;

// `render SCENE --tiles K/N`: part K of N of the scene's frame, or with `frames` of each frame
// of its range, rendered by the raymarcher into OUT/<scene>/ (OUT/<scene>/<frame>/), and
// OUT/shard.json naming them. `overrides`: the scene's --set (and --frames) overrides, for
// the frames' keys; `settings`: the command's arguments that the parts of one render share.
void renderTiles(LoadedScene& scene, const core::FramePart& part, bool frames,
                 const std::vector<std::string>& overrides, const nlohmann::json& settings,
                 const std::string& commandLine, const std::filesystem::path& out);

// `run --tiles K/N`, after runSuite has checked every input: part K of every reference the run
// takes (each still scene's, each frame of each sequence's) into OUT/reference_tiles/<key>/,
// and OUT/shard.json with the run's arguments, from which the merge runs the whole run.
ExitCode runTiles(std::vector<LoadedScene>& scenes, const core::FramePart& part,
                  const RunOptions& options, const std::string& thresholdsFile);

// `sweep --tiles K/N`, after runSweep has checked every input: the same for every reference
// its combinations take (`walk`), with the sweep's arguments.
ExitCode sweepTiles(const ReferenceWalk& walk, const core::FramePart& part,
                    const SweepOptions& options);

// `merge` of the parts of `render --tiles`, `run --tiles` or `sweep --tiles`, whose manifests
// the merge has found to belong together (one command, the same N, every K once, the same
// settings). Checks that every part holds the same references, and for a run or a sweep that
// they are the references it takes now (the same scene files and the files they name,
// overrides, raymarch settings and raymarcher build), before anything is written; then joins
// each reference's parts into OUT/<folder>/ (render) or OUT/reference_cache/<key>/ (run or
// sweep, which then runs with that cache). Returns the run's or the sweep's exit code, or Pass.
ExitCode mergeTiles(const std::vector<std::filesystem::path>& dirs,
                    const std::vector<nlohmann::json>& manifests, const std::filesystem::path& out,
                    const MergeOptions& options);

}  // namespace twinrender::app
