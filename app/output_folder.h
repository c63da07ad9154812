// The folders a command writes into. Every command that writes checks its output folder
// before any work starts (a folder that refuses writes is exit 4 at once, not after minutes
// of rendering), and writes each report as a whole or not at all: a full disk or a signal
// never leaves half a report (docs/design.md, "Principles").
#pragma once

#include <filesystem>
#include <functional>

namespace twinrender::app {

// Makes `dir` (with its parents) and checks that a file can be written in it; throws
// core::OutputError naming the folder and the system's reason.
void prepareOutputFolder(const std::filesystem::path& dir);

// Writes files that belong together into `dir`: `write` writes them under a staging folder
// inside `dir` (the same file system), laid out as in `dir`, and they are renamed into place
// only once every one is written. On any failure the staging folder is removed and the files
// of `dir` are as they were. Throws core::OutputError when the file system refuses.
void writeTogether(const std::filesystem::path& dir,
                   const std::function<void(const std::filesystem::path& staging)>& write);

}  // namespace twinrender::app
