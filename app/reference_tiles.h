// One reference frame split across machines (docs/cli.md, "Tiles"): `render --tiles K/N` and
// `run --tiles K/N` render part K of N of each reference frame with the raymarcher
// (core/frame_part.h), and `twinrender merge` joins the N parts into the frames one render
// gives, bit for bit (core/part_join.h). A part's output folder carries a manifest,
// shard.json (app/shard.h), with "split": "tiles" and "references": [{"folder" (inside the
// part's folder, holding raymarch.exr|png|json), "key" and "what" (app/reference_cache.h's key
// of the frame and what went into it), "scene", and "frame" for a sequence's frame}].
//
// A run's parts render no real-time frame and compare nothing: the merge joins the
// references into OUT/reference_cache and runs the run there, every reference a cache hit.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/exit_code.h"
#include "app/merge_command.h"
#include "app/render_job.h"
#include "app/suite_commands.h"
#include "core/frame_part.h"

namespace twinrender::app {

// "K/N" of --tiles; throws core::InputError naming the option.
core::FramePart parseTiles(const std::string& text);

// `render SCENE --tiles K/N`: part K of N of the scene's frame, or with `frames` of each frame
// of its range, rendered by the raymarcher into OUT/<scene>/ (OUT/<scene>/<frame>/), and
// OUT/shard.json naming them. `overrides`: the scene's --set (and --frames) overrides, for
// the frames' keys; `settings`: the command's arguments that the parts of one render share.
void renderTiles(LoadedScene& scene, const core::FramePart& part, bool frames,
                 const std::vector<std::string>& overrides, const nlohmann::json& settings,
                 const std::string& commandLine, Devices& devices,
                 const std::filesystem::path& out);

// `run --tiles K/N`, after runSuite has checked every input: part K of every reference the run
// takes (each still scene's, each frame of each sequence's) into
// OUT/reference_tiles/<key>/, and OUT/shard.json with the run's arguments, from which the
// merge runs the whole run.
ExitCode runTiles(std::vector<LoadedScene>& scenes, const core::FramePart& part,
                  const RunOptions& options, const std::string& thresholdsFile, Devices& devices);

// `merge` of the parts of `render --tiles` or `run --tiles`, whose manifests the merge has
// found to belong together (one command, the same N, every K once, the same settings). Checks
// that every part holds the same references, and for a run that they are the references its
// scenes take now (the same scene files and the files they name, overrides, raymarch settings
// and raymarcher build), before anything is written; then joins each reference's parts into
// OUT/<folder>/ (render) or OUT/reference_cache/<key>/ (run, which then runs as runSuite with
// that cache). Returns the run's exit code, or Pass.
ExitCode mergeTiles(const std::vector<std::filesystem::path>& dirs,
                    const std::vector<nlohmann::json>& manifests, const std::filesystem::path& out,
                    const MergeOptions& options);

}  // namespace twinrender::app
