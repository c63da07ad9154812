// The folders a command may write into: the output folder, cache folder and files the user
// named on the command line, never a place a scene file, thresholds file, baseline or shard
// manifest names. A command registers what the user named before any work starts
// (app/main.cpp); from then on every file written through writeFileAtomically and every
// folder made through makeFolders must lie inside one of them, after symbolic links are
// resolved, or it is an OutputError (exit 4) naming the path. A file the suite reads may thus
// name at worst a wrong place inside the output folder, never one outside it. A process that
// registers nothing (a library's tests) writes where it is told.
#pragma once

#include <filesystem>
#include <string_view>

namespace twinrender::core {

// Lets this process write inside `dir` (a folder, made or not yet made) or to `dir` itself (a
// file the user named, such as --junit FILE).
void allowWritesUnder(const std::filesystem::path& dir);
// Forgets every registered folder (tests).
void clearWriteRoots();

// Throws OutputError when folders are registered and `path` is inside none of them.
void checkWriteAllowed(const std::filesystem::path& path);
// checkWriteAllowed, then std::filesystem::create_directories; OutputError on failure.
void makeFolders(const std::filesystem::path& dir);

// Whether `path` is `root` or lies inside it once both are made absolute and their existing
// parts' symbolic links resolved.
bool isInside(const std::filesystem::path& root, const std::filesystem::path& path);
// Throws InputError "`what`: PATH is outside ROOT; ..." unless isInside(root, path): for the
// files a manifest or report names, which must be inside the folder it was given in.
void requireInside(const std::filesystem::path& root, const std::filesystem::path& path,
                   std::string_view what);

}  // namespace twinrender::core
