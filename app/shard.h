// Scale-out (docs/cli.md): `run` and `sweep` take --shard K/N and do every N-th
// item of their work starting at the (K-1)-th, so N machines (a CI matrix, a Slurm array job)
// share it; each shard's output folder carries a manifest, shard.json, from which
// `twinrender merge` rebuilds the report one unsharded run gives.
//
// shard.json: {"format": "twinrender-shard", "version": 1, "command": "run" | "sweep",
//   "shard": K, "of": N, "settings": {the command's normalised arguments: what must be equal
//   for shards to belong together}, "created", "command_line", and per command: run ->
//   "scenes": [every scene name of the whole run, in its order], "reports": [the full report
//   of each scene this shard ran], "junit": bool; sweep -> "combinations": the product's size,
//   "indices": [the combinations this shard ran]}.
// The parts of `render --tiles K/N` and `run --tiles K/N` carry the same manifest with
// "split": "tiles" (a shard's is "scenes", or none) and their "references"
// (app/reference_tiles.h); "shard" and "of" are then the part's K and N.
#pragma once

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/exit_code.h"

namespace twinrender::app {

struct Shard {
    int index = 1;  // K, 1..count
    int count = 1;  // N, >= 1

    // Whether item i (0-based, in the command's deterministic order) belongs to this shard.
    bool takes(std::size_t i) const {
        return static_cast<int>(i % static_cast<std::size_t>(count)) == index - 1;
    }
};

// "K/N" with 1 <= K <= N; throws core::InputError naming the option (`option`: --shard or
// --tiles) and what is wrong.
Shard parseShard(const std::string& text, const std::string& option = "--shard");

// Writes DIR/shard.json (atomically) from the command-specific part `manifest`, adding the
// format, version, shard and count.
void writeShardManifest(const Shard& shard, nlohmann::json manifest,
                        const std::filesystem::path& dir);

// Reads DIR/shard.json; throws core::InputError naming the file when it is missing or not a
// shard manifest.
nlohmann::json readShardManifest(const std::filesystem::path& dir);

// The folder `relative` (a scene's name, a combination's or a tile's folder, as the manifest
// in `shard` names it) inside `shard`; core::InputError naming the manifest and `key` when it
// would lead out.
std::filesystem::path folderInShard(const std::filesystem::path& shard, const std::string& relative,
                                    const std::string& key);

// Copies a folder's tree into `to` (hard links where the file system allows, else copies),
// replacing files that exist there.
void copyTree(const std::filesystem::path& from, const std::filesystem::path& to);

}  // namespace twinrender::app
