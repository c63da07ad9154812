#include "app/shard.h"

#include <fmt/format.h>

#include <cstdio>
#include <fstream>

#include "core/error.h"
#include "core/folder_name.h"
#include "core/image_io.h"
#include "core/write_roots.h"

namespace twinrender::app {

namespace fs = std::filesystem;
using nlohmann::json;

Shard parseShard(const std::string& text, const std::string& option) {
    const auto slash = text.find('/');
    auto number = [&](const std::string& part) {
        if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos ||
            part.size() > 6)
            throw core::InputError(fmt::format(
                "{} {}: expected K/N with whole numbers, 1 <= K <= N (e.g. 2/4)", option, text));
        return std::stoi(part);
    };
    if (slash == std::string::npos)
        throw core::InputError(
            fmt::format("{} {}: expected K/N, 1 <= K <= N (e.g. 2/4)", option, text));
    Shard s{number(text.substr(0, slash)), number(text.substr(slash + 1))};
    if (s.count < 1 || s.index < 1 || s.index > s.count)
        throw core::InputError(fmt::format("{} {}: K must be between 1 and N (here K = {}, N = {})",
                                           option, text, s.index, s.count));
    return s;
}

void writeShardManifest(const Shard& shard, json manifest, const fs::path& dir) {
    manifest["format"] = "twinrender-shard";
    manifest["version"] = 1;
    manifest["shard"] = shard.index;
    manifest["of"] = shard.count;
    core::makeFolders(dir);
    core::writeTextFile(dir / "shard.json", manifest.dump(2) + "\n");
}

json readShardManifest(const fs::path& dir) {
    const fs::path file = dir / "shard.json";
    std::ifstream in(file);
    if (!in)
        throw core::InputError(
            fmt::format("{}: no shard manifest; merge takes the --out folders of "
                        "`run --shard K/N` or `sweep --shard K/N`",
                        file.string()));
    const json j = json::parse(in, nullptr, false);
    // Values are compared and their types checked, never converted: a damaged manifest is
    // bad input naming the file and the key.
    if (j.is_discarded() || !j.is_object() || !j.contains("format") ||
        j["format"] != "twinrender-shard")
        throw core::InputError(fmt::format("{}: not a twinrender shard manifest", file.string()));
    if (!j.contains("version") || j["version"] != 1)
        throw core::InputError(fmt::format("{}: manifest version {} is not supported",
                                           file.string(), j.value("version", json()).dump()));
    for (const char* key : {"command", "shard", "of", "settings"})
        if (!j.contains(key))
            throw core::InputError(fmt::format("{}: no \"{}\"", file.string(), key));
    const auto typed = [&](const char* key, bool ok, const char* what) {
        if (!ok)
            throw core::InputError(
                fmt::format("{}: \"{}\" is {}, not {}", file.string(), key, j[key].dump(), what));
    };
    typed("command", j["command"].is_string(), "a command name");
    typed("shard", j["shard"].is_number_integer(), "a shard number");
    typed("of", j["of"].is_number_integer() && j["of"].get<long long>() >= 1,
          "a shard count of 1 or more");
    typed("settings", j["settings"].is_object(), "an object");
    return j;
}

fs::path folderInShard(const fs::path& shard, const std::string& relative, const std::string& key) {
    const fs::path rel(relative);
    std::string problem = rel.is_absolute() ? "is an absolute path" : "";
    for (const fs::path& part : rel)
        if (problem.empty()) problem = core::folderNameProblem(part.string());
    if (!problem.empty())
        throw core::InputError(
            fmt::format("{}: {} '{}' {}; a manifest names only folders inside its shard's folder",
                        (shard / "shard.json").string(), key, core::printable(relative), problem));
    core::requireInside(shard, shard / rel, (shard / "shard.json").string());
    return shard / rel;
}

void copyTree(const fs::path& from, const fs::path& to) {
    try {
        core::makeFolders(to);
        for (const auto& e : fs::recursive_directory_iterator(from)) {
            const fs::path target = to / fs::relative(e.path(), from);
            // A link could lead out of the shard's folder: merge reads only inside it.
            if (e.is_symlink())
                throw core::InputError(fmt::format(
                    "{}: a symbolic link in a shard's folder; merge copies only the files "
                    "`run --shard` and `sweep --shard` write",
                    e.path().string()));
            if (e.is_directory()) {
                core::makeFolders(target);
                continue;
            }
            if (!e.is_regular_file()) continue;
            fs::remove(target);
            std::error_code ec;
            fs::create_hard_link(e.path(), target, ec);
            // A copy under a temporary name, renamed: a full disk leaves no half file.
            if (ec)
                core::writeFileAtomically(target, [&](const fs::path& tmp) {
                    fs::copy_file(e.path(), tmp, fs::copy_options::overwrite_existing);
                });
        }
    } catch (const fs::filesystem_error& e) {
        throw core::OutputError(fmt::format("{}: cannot copy {} there ({})", to.string(),
                                            e.path1().string(), e.code().message()));
    }
}

}  // namespace twinrender::app
