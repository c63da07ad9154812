#include "app/merge_command.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>

#include "app/comparison.h"
#include "app/output_folder.h"
#include "app/reference_tiles.h"
#include "app/shard.h"
#include "app/suite_commands.h"
#include "app/sweep_command.h"
#include "core/error.h"
#include "core/write_roots.h"
#include "report/junit.h"
#include "report/report.h"
#include "report/report_json.h"
#include "report/sweep_report.h"

namespace twinrender::app {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

ExitCode mergeRun(const std::vector<fs::path>& dirs, const std::vector<json>& manifests,
                  const fs::path& out, const MergeOptions& o) {
    const json& first = manifests.front();
    const auto order = first.at("scenes").get<std::vector<std::string>>();
    std::map<std::string, report::SceneReport> reports;
    std::map<std::string, fs::path> from;
    for (std::size_t i = 0; i < dirs.size(); ++i)
        for (const json& r : manifests[i].at("reports")) {
            report::SceneReport s =
                report::sceneReportFromJson(r, (dirs[i] / "shard.json").string());
            folderInShard(dirs[i], s.name, "the scene name");
            if (reports.count(s.name))
                throw core::InputError(
                    fmt::format("{}: scene '{}' is also in {}; the shards overlap",
                                dirs[i].string(), s.name, from[s.name].string()));
            from[s.name] = dirs[i];
            reports.emplace(s.name, std::move(s));
        }
    report::RunReport run;
    run.createdAt = nowUtc();
    run.commandLine = o.commandLine;
    run.thresholdsFile = first.at("settings").value("thresholds", "");
    run.baselineFile = first.at("settings").value("baseline", "");
    for (const std::string& name : order) {
        const auto it = reports.find(name);
        if (it == reports.end())
            throw core::InputError(
                fmt::format("scene '{}' is in none of the shards; was a shard cut short?", name));
        run.scenes.push_back(std::move(it->second));
        reports.erase(it);
    }
    if (!reports.empty())
        throw core::InputError(fmt::format("scene '{}' of {} is not in the run's list",
                                           reports.begin()->first,
                                           from[reports.begin()->first].string()));
    // The scenes' folders and the report appear together or not at all.
    writeTogether(out, [&](const fs::path& staging) {
        for (const std::string& name : order)
            if (const fs::path dir = folderInShard(from[name], name, "the scene name");
                fs::is_directory(dir))
                copyTree(dir, staging / name);
        report::writeReport(run, staging);
        if (first.value("junit", false)) report::writeJunit(run, staging / "junit.xml");
    });
    std::printf("merged %zu shards, %zu scenes: %s -> %s\n", dirs.size(), run.scenes.size(),
                std::string(compare::toString(run.status())).c_str(), (out / "index.html").c_str());
    printAnnotations(run, o.annotations);
    return exitCodeOf(run.status());
}

ExitCode mergeSweep(const std::vector<fs::path>& dirs, const std::vector<json>& manifests,
                    const fs::path& out, const std::string& commandLine) {
    const std::size_t total = manifests.front().at("combinations").get<std::size_t>();
    std::optional<report::SweepReport> merged;
    std::map<std::size_t, fs::path> seen;
    for (std::size_t i = 0; i < dirs.size(); ++i) {
        if (manifests[i].at("combinations").get<std::size_t>() != total)
            throw core::InputError(fmt::format(
                "{}: {} combinations, {} has {}; not shards of one sweep", dirs[i].string(),
                manifests[i].at("combinations").get<std::size_t>(), dirs[0].string(), total));
        std::ifstream in(dirs[i] / "sweep.json");
        const json j = json::parse(in, nullptr, false);
        if (!in || j.is_discarded())
            throw core::InputError(
                fmt::format("{}: missing or not JSON", (dirs[i] / "sweep.json").string()));
        report::SweepReport part = report::sweepFromJson(j, (dirs[i] / "sweep.json").string());
        for (report::SweepRow& row : part.rows) {
            folderInShard(dirs[i], row.dir, "the combination's folder");
            if (row.index >= total || seen.count(row.index))
                throw core::InputError(
                    fmt::format("{}: combination {} {}", dirs[i].string(), row.index,
                                row.index >= total ? "is beyond the sweep"
                                                   : "is also in " + seen[row.index].string()));
            seen[row.index] = dirs[i];
        }
        if (!merged) {
            merged = std::move(part);
        } else {
            for (auto& row : part.rows) merged->rows.push_back(std::move(row));
        }
    }
    if (seen.size() != total)
        for (std::size_t k = 0; k < total; ++k)
            if (!seen.count(k))
                throw core::InputError(fmt::format(
                    "combination {} is in none of the shards; was a shard cut short?", k));
    std::sort(merged->rows.begin(), merged->rows.end(),
              [](const auto& a, const auto& b) { return a.index < b.index; });
    merged->createdAt = nowUtc();
    merged->commandLine = commandLine;
    // The combinations' folders, the references and the report appear together or not at all.
    writeTogether(out, [&](const fs::path& staging) {
        for (const auto& row : merged->rows) {
            const fs::path dir =
                folderInShard(seen.at(row.index), row.dir, "the combination's folder");
            if (fs::is_directory(dir)) copyTree(dir, staging / row.dir);
        }
        for (const fs::path& dir : dirs)
            if (fs::is_directory(dir / "reference_cache"))
                copyTree(dir / "reference_cache", staging / "reference_cache");
        report::writeSweepReport(*merged, staging);
    });
    std::printf("merged %zu shards, %zu combinations -> %s, %s\n", dirs.size(), merged->rows.size(),
                (out / "sweep.csv").c_str(), (out / "index.html").c_str());
    return finishSweep(*merged);
}

// What a manifest splits: "scenes" (or a sweep's combinations: --shard) or "tiles" (--tiles).
std::string splitOf(const json& manifest) {
    return manifest.value("split", "scenes");
}

ExitCode mergeManifests(const std::vector<fs::path>& dirs, const std::vector<json>& manifests,
                        const fs::path& out, const MergeOptions& o) {
    // They belong together: one command, one split, one N, every K once, the same settings.
    const json& first = manifests.front();
    const int n = first.at("of").get<int>();
    const std::string split = splitOf(first);
    const auto kind = [](const std::string& s) {
        return s == "tiles" ? "tiles of a frame (--tiles)" : "shards of the work (--shard)";
    };
    const char* part = split == "tiles" ? "tile" : "shard";
    const std::string command = first.at("command").get<std::string>();
    std::map<int, fs::path> shards;
    for (std::size_t i = 0; i < dirs.size(); ++i) {
        const json& m = manifests[i];
        if (m.at("command") != first.at("command"))
            throw core::InputError(
                fmt::format("{} is a {} of `{}`, {} of `{}`; merge the parts of one command",
                            dirs[i].string(), part, m.at("command").get<std::string>(),
                            dirs[0].string(), first.at("command").get<std::string>()));
        if (splitOf(m) != split)
            throw core::InputError(fmt::format("{} holds {}, {} {}; merge the parts of one split",
                                               dirs[i].string(), kind(splitOf(m)), dirs[0].string(),
                                               kind(split)));
        if (m.at("of").get<int>() != n)
            throw core::InputError(fmt::format("{} is {} {}/{}, {} is {} {}/{}: not {}s of one {}",
                                               dirs[i].string(), part, m.at("shard").get<int>(),
                                               m.at("of").get<int>(), dirs[0].string(), part,
                                               first.at("shard").get<int>(), n, part, command));
        if (m.at("settings") != first.at("settings")) {
            std::string diff;
            for (const auto& [k, v] : m.at("settings").items())
                if (!first.at("settings").contains(k) || first.at("settings").at(k) != v)
                    diff += fmt::format("{}{}: {} vs {}", diff.empty() ? "" : "; ", k,
                                        first.at("settings").value(k, json()).dump(), v.dump());
            throw core::InputError(
                fmt::format("{} and {} were run with different settings ({}); not {}s of one {}",
                            dirs[0].string(), dirs[i].string(), diff, part, command));
        }
        const int k = m.at("shard").get<int>();
        if (shards.count(k))
            throw core::InputError(fmt::format("{} and {} are both {} {}/{}", shards[k].string(),
                                               dirs[i].string(), part, k, n));
        shards[k] = dirs[i];
    }
    for (int k = 1; k <= n; ++k)
        if (!shards.count(k))
            throw core::InputError(
                fmt::format("{} {}/{} is missing; give all {} {} folders", part, k, n, n, part));
    // The tiles' merge checks the frames they hold before it writes.
    if (split == "tiles") return mergeTiles(dirs, manifests, out, o);
    prepareOutputFolder(out);
    if (command == "run") return mergeRun(dirs, manifests, out, o);
    if (command == "sweep") return mergeSweep(dirs, manifests, out, o.commandLine);
    throw core::InputError(
        fmt::format("{}: unknown command '{}' in the manifest", dirs[0].string(), command));
}

}  // namespace

ExitCode runMerge(const MergeOptions& o) {
    if (o.inputs.empty()) throw core::InputError("merge: give the shard folders to merge");
    std::vector<fs::path> dirs;
    std::vector<json> manifests;
    const fs::path out = fs::weakly_canonical(o.out);
    for (const auto& in : o.inputs) {
        if (!fs::is_directory(in)) throw core::InputError(fmt::format("{}: no such folder", in));
        if (fs::weakly_canonical(in) == out)
            throw core::InputError(
                fmt::format("--out {}: is one of the shards; merge into a new folder", o.out));
        dirs.emplace_back(in);
        manifests.push_back(readShardManifest(in));
    }
    try {
        return mergeManifests(dirs, manifests, out, o);
    } catch (const json::exception& e) {
        // A part of a manifest that is not what `run` or `sweep` wrote.
        std::string files;
        for (const fs::path& d : dirs)
            files += (files.empty() ? "" : ", ") + (d / "shard.json").string();
        throw core::InputError(
            fmt::format("{}: a shard manifest is damaged ({})", files, e.what()));
    }
}

}  // namespace twinrender::app
