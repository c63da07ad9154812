#include "app/reference_tiles.h"

#include <fmt/format.h>

#include <cstdio>
#include <functional>
#include <optional>
#include <set>

#include "app/comparison.h"
#include "app/output_folder.h"
#include "app/reference_cache.h"
#include "app/sequence_run.h"
#include "app/shard.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/part_join.h"
#include "core/sequence.h"

namespace twinrender::app {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Every reference frame a run takes of its scenes: a still scene's, or each frame of a
// sequence's range; the key of each is of the run's --set overrides.
void walkRun(std::vector<LoadedScene>& scenes, const std::vector<std::string>& sets,
             const ReferenceVisit& visit) {
    for (LoadedScene& s : scenes) {
        if (!s.scene.sequence) {
            visit(s, sets, std::nullopt);
            continue;
        }
        for (const std::int64_t n : core::sequenceFrames(s.scene)) {
            setFrame(s, n);
            visit(s, sets, n);
        }
    }
}

// A reference as the manifest lists it.
json referenceEntry(const std::string& folder, const std::string& key, const json& what,
                    const LoadedScene& s, std::optional<std::int64_t> frame) {
    json entry = {{"folder", folder}, {"key", key}, {"what", what}, {"scene", s.scene.name}};
    if (frame) entry["frame"] = *frame;
    return entry;
}

// "planet" or "splash frame 16": a reference for the terminal and the errors.
std::string label(const json& entry) {
    const std::string scene = entry.value("scene", "?");
    return entry.contains("frame") ? fmt::format("{} frame {}", scene, entry.at("frame").dump())
                                   : scene;
}

// Renders part `part` of the scene's frame into OUT/folder and says so.
void renderPart(const LoadedScene& s, core::Renderer& renderer, const core::FramePart& part,
                const fs::path& out, const std::string& folder) {
    const core::Frame f = render(renderer, "raymarch", s, nullptr, part);
    writeRender(s, f, out / folder);
    std::printf("%s: raymarch tile %d/%d, %d of %d rows of tiles, %.1f ms -> %s\n",
                s.scene.name.c_str(), part.index, part.count,
                part.rowsHeld(f.part->height, f.part->tileSize),
                core::FramePart{}.rowsHeld(f.part->height, f.part->tileSize),
                f.timingsMs.at("total"), (out / folder / "raymarch.exr").c_str());
    std::fflush(stdout);
}

void writeTilesManifest(const core::FramePart& part, const std::string& command,
                        const json& settings, const json& references,
                        const std::string& commandLine, const fs::path& out) {
    const json manifest = {{"command", command},   {"split", "tiles"},
                           {"settings", settings}, {"references", references},
                           {"created", nowUtc()},  {"command_line", commandLine}};
    writeTogether(out, [&](const fs::path& staging) {
        writeShardManifest({.index = part.index, .count = part.count}, manifest, staging);
    });
}

// The arguments `run` and `sweep` share, as their tiles' manifest holds them.
template <typename Options>
json sharedSettings(const Options& o) {
    return {{"sets", o.sets},          {"thresholds", o.thresholds},  {"ppd", o.ppd},
            {"flip_over", o.flipOver}, {"require_gpu", o.requireGpu}, {"self_check", o.selfCheck}};
}

// And back, for the command the merge runs into `out`, its references from
// OUT/reference_cache.
template <typename Options>
Options fromSharedSettings(const json& settings, const fs::path& out,
                           const std::string& commandLine) {
    Options o;
    o.sets = settings.at("sets").get<std::vector<std::string>>();
    o.thresholds = settings.at("thresholds").get<std::string>();
    o.ppd = settings.at("ppd").get<double>();
    o.flipOver = settings.at("flip_over").get<double>();
    o.requireGpu = settings.at("require_gpu").get<bool>();
    o.selfCheck = settings.at("self_check").get<bool>();
    o.out = out.string();
    o.cache = (out / "reference_cache").string();
    o.commandLine = commandLine;
    return o;
}

// The run's arguments that its tiles share and its merge runs with: the thresholds file as
// the run found it.
json runSettings(const RunOptions& o, const std::string& thresholdsFile) {
    json j = sharedSettings(o);
    j["thresholds"] = thresholdsFile;
    j["inputs"] = o.inputs;
    j["baseline"] = o.baseline;
    j["junit"] = !o.junit.empty();
    j["tests"] = o.tests;
    j["external"] = {{"command", o.external.command},
                     {"images", o.external.images.string()},
                     {"timeout", o.external.timeoutSeconds}};
    return j;
}

RunOptions runFromSettings(const json& settings, const fs::path& out, const MergeOptions& m) {
    RunOptions o = fromSharedSettings<RunOptions>(settings, out, m.commandLine);
    o.inputs = settings.at("inputs").get<std::vector<std::string>>();
    o.baseline = settings.at("baseline").get<std::string>();
    if (settings.at("junit").get<bool>()) o.junit = (out / "junit.xml").string();
    o.tests = settings.at("tests").get<std::vector<std::string>>();
    const json& external = settings.at("external");
    o.external.command = external.at("command").get<std::string>();
    o.external.images = external.at("images").get<std::string>();
    o.external.timeoutSeconds = external.at("timeout").get<double>();
    o.annotations = m.annotations;
    return o;
}

json sweepSettings(const SweepOptions& o) {
    json j = sharedSettings(o);
    j["scene"] = o.scene;
    j["vary"] = o.vary;
    j["metric"] = o.metric;
    j["frames"] = o.frames;
    return j;
}

SweepOptions sweepFromSettings(const json& settings, const fs::path& out, const MergeOptions& m) {
    SweepOptions o = fromSharedSettings<SweepOptions>(settings, out, m.commandLine);
    o.scene = settings.at("scene").get<std::string>();
    o.vary = settings.at("vary").get<std::vector<std::string>>();
    o.metric = settings.at("metric").get<std::string>();
    o.frames = settings.at("frames").get<int>();
    return o;
}

// What differs between two accounts of a reference (app/reference_cache.h's "what"), as
// "/raymarch/spp 1 against 4; ...".
std::string differences(const json& a, const json& b) {
    std::string out;
    for (const json& op : json::diff(a, b)) {
        const std::string path = op.at("path").get<std::string>();
        const json::json_pointer at(path);
        out += fmt::format("{}{} {} against {}", out.empty() ? "" : "; ", path,
                           a.contains(at) ? a.at(at).dump() : "nothing",
                           b.contains(at) ? b.at(at).dump() : "nothing");
    }
    // The same account, another key: a file it names has other contents.
    return out.empty() ? "the scene file or a file it names has changed" : out;
}

// Every part holds the same references, in the same order.
void checkSameReferences(const std::vector<fs::path>& dirs, const std::vector<json>& manifests) {
    const json& refs = manifests.front().at("references");
    for (std::size_t i = 1; i < dirs.size(); ++i) {
        const json& other = manifests[i].at("references");
        if (other == refs) continue;
        if (other.size() != refs.size())
            throw core::InputError(
                fmt::format("{} holds tiles of {} frames, {} of {}: not tiles of one render",
                            dirs[i].string(), other.size(), dirs[0].string(), refs.size()));
        for (std::size_t k = 0; k < refs.size(); ++k)
            if (other[k] != refs[k])
                throw core::InputError(fmt::format(
                    "{} and {} hold tiles of different frames: {}: {}; not tiles of one render",
                    dirs[0].string(), dirs[i].string(), label(refs[k]),
                    differences(refs[k].value("what", json()), other[k].value("what", json()))));
    }
}

// The references the command takes now (`walk`) are those its tiles hold: the same scene
// files and the files they name, overrides, raymarch settings and raymarcher build.
void checkReferences(const std::string& command, const ReferenceWalk& walk, const json& refs) {
    std::vector<json> now;
    std::set<std::string> seen;
    walk([&](LoadedScene& s, const std::vector<std::string>& overrides,
             std::optional<std::int64_t> frame) {
        const auto [key, what] = referenceKey(s, overrides);
        if (seen.insert(key).second) now.push_back(referenceEntry("", key, what, s, frame));
    });
    for (std::size_t k = 0; k < std::max(now.size(), refs.size()); ++k) {
        if (k >= refs.size())
            throw core::InputError(
                fmt::format("{}: this reference is taken now and none of the tiles holds it; "
                            "render the tiles again",
                            label(now[k])));
        if (k >= now.size() || now[k].at("key") != refs[k].at("key"))
            throw core::InputError(fmt::format(
                "{}: the tiles were rendered for another reference than the {} takes now ({}); "
                "merge with the build, scene files and overrides the tiles were rendered with, or "
                "render them again",
                label(refs[k]), command,
                k >= now.size() ? "it takes none"
                                : differences(refs[k].at("what"), now[k].at("what"))));
    }
}

// Part `part` of every reference `walk` visits, each once, into OUT/reference_tiles/<key>/,
// and the manifest.
void renderReferenceTiles(const ReferenceWalk& walk, const core::FramePart& part,
                          const std::string& command, const json& settings,
                          const std::string& commandLine, const fs::path& out) {
    prepareOutputFolder(out);
    Devices devices;
    json references = json::array();
    std::set<std::string> seen;
    walk([&](LoadedScene& s, const std::vector<std::string>& overrides,
             std::optional<std::int64_t> frame) {
        const auto [key, what] = referenceKey(s, overrides);
        if (!seen.insert(key).second) return;
        const std::string folder = "reference_tiles/" + key;
        renderPart(s, *makeRenderer("raymarch", devices, s), part, out, folder);
        references.push_back(referenceEntry(folder, key, what, s, frame));
    });
    writeTilesManifest(part, command, settings, references, commandLine, out);
    std::printf(
        "tile %d/%d of %zu reference frames -> %s; `twinrender merge` of the %d tiles' "
        "folders joins them and runs the %s\n",
        part.index, part.count, references.size(), out.c_str(), part.count, command.c_str());
}

// The parts of one frame, from the same folder of each part's folder, joined; `meta` receives
// the first part's JSON.
core::Frame joinParts(const std::vector<fs::path>& dirs, const std::string& folder, json& meta) {
    core::PartJoin join;
    for (const fs::path& dir : dirs) {
        const fs::path at = folderInShard(dir, folder, "the tile's folder");
        json j;
        core::Frame part = core::readFrame(at, "raymarch", &j);
        if (meta.is_null()) meta = j;
        join.add(std::move(part), (at / "raymarch.json").string());
    }
    const json::json_pointer exposure("/camera/exposure");
    if (!meta.contains(exposure) || !meta.at(exposure).is_number())
        throw core::InputError(fmt::format("{}: no camera.exposure",
                                           (dirs.front() / folder / "raymarch.json").string()));
    core::Frame whole = join.frame(static_cast<float>(meta.at(exposure).get<double>()));
    // The JSON beside the frame: the render's own keys (scene, camera, ...) and each part's
    // device and times.
    for (const char* key : {"renderer", "device", "settings", "particle_count", "resolution",
                            "counters", "timings_ms", "tile"})
        meta.erase(key);
    meta["tiles"] = join.parts();
    return whole;
}

}  // namespace

core::FramePart parseTiles(const std::string& text) {
    const Shard s = parseShard(text, "--tiles");
    return {.index = s.index, .count = s.count};
}

void refuseTilesWith(const std::string& command, const std::string& shardSplits, bool shard,
                     bool cache) {
    if (shard)
        throw core::InputError(fmt::format(
            "{} --tiles with --shard: give one; --shard splits {}, --tiles each reference frame",
            command, shardSplits));
    if (cache)
        throw core::InputError(fmt::format(
            "{0} --tiles with --cache: a tile job renders its part of every reference; the merge "
            "keeps the whole references in OUT/reference_cache, which a later {0} can take with "
            "--cache",
            command));
}

void renderTiles(LoadedScene& s, const core::FramePart& part, bool frames,
                 const std::vector<std::string>& overrides, const json& settings,
                 const std::string& commandLine, const fs::path& out) {
    Devices devices;
    const auto renderer = makeRenderer("raymarch", devices, s);
    prepareOutputFolder(out / s.scene.name);
    json references = json::array();
    const auto one = [&](const std::string& folder, std::optional<std::int64_t> frame) {
        const auto [key, what] = referenceKey(s, overrides);
        renderPart(s, *renderer, part, out, folder);
        references.push_back(referenceEntry(folder, key, what, s, frame));
    };
    // As `render` writes them: without --frames the scene's (a sequence's first) frame in
    // OUT/<scene>/, with it each frame of the range in OUT/<scene>/<frame>/.
    if (!frames) one(s.scene.name, std::nullopt);
    if (frames)
        for (const std::int64_t n : core::sequenceFrames(s.scene)) {
            setFrame(s, n);
            one(s.scene.name + "/" + frameFolder(n),
                s.scene.sequence ? std::optional<std::int64_t>(n) : std::nullopt);
        }
    writeTilesManifest(part, "render", settings, references, commandLine, out);
}

ExitCode runTiles(std::vector<LoadedScene>& scenes, const core::FramePart& part,
                  const RunOptions& o, const std::string& thresholdsFile) {
    renderReferenceTiles([&](const ReferenceVisit& visit) { walkRun(scenes, o.sets, visit); }, part,
                         "run", runSettings(o, thresholdsFile), o.commandLine, o.out);
    return ExitCode::Pass;
}

ExitCode sweepTiles(const ReferenceWalk& walk, const core::FramePart& part, const SweepOptions& o) {
    renderReferenceTiles(walk, part, "sweep", sweepSettings(o), o.commandLine, o.out);
    return ExitCode::Pass;
}

ExitCode mergeTiles(const std::vector<fs::path>& dirs, const std::vector<json>& manifests,
                    const fs::path& out, const MergeOptions& o) {
    const json& first = manifests.front();
    const std::string command = first.at("command").get<std::string>();
    if (command != "render" && command != "run" && command != "sweep")
        throw core::InputError(
            fmt::format("{}: tiles of `{}`; `render`, `run` and `sweep` render tiles",
                        (dirs.front() / "shard.json").string(), command));
    checkSameReferences(dirs, manifests);
    const json refs = first.at("references");
    // Every part's files are there before anything is written.
    for (const fs::path& dir : dirs)
        for (const json& ref : refs) {
            const fs::path at =
                folderInShard(dir, ref.at("folder").get<std::string>(), "the tile's folder");
            // (A part that holds no row of tiles has no raymarch.exr: readFrame knows.)
            if (!fs::is_regular_file(at / "raymarch.json"))
                throw core::InputError(
                    fmt::format("{}: missing; the tile of {} is not whole (was its job cut short?)",
                                (at / "raymarch.json").string(), label(ref)));
        }
    // A run or a sweep runs after the join, as it was given to the tile jobs.
    std::optional<RunOptions> run;
    std::optional<SweepOptions> sweep;
    if (command == "run") {
        run = runFromSettings(first.at("settings"), out, o);
        checkReferences(
            command,
            [&](const ReferenceVisit& visit) {
                std::vector<LoadedScene> scenes;
                for (const fs::path& file : runSceneFiles(*run))
                    scenes.push_back(loadScene(file, run->sets));
                walkRun(scenes, run->sets, visit);
            },
            refs);
    }
    if (command == "sweep") {
        sweep = sweepFromSettings(first.at("settings"), out, o);
        checkReferences(
            command, [&](const ReferenceVisit& visit) { forEachSweepReference(*sweep, visit); },
            refs);
    }
    const bool cached = run || sweep;
    // The joined frames appear together or not at all.
    writeTogether(out, [&](const fs::path& staging) {
        for (const json& ref : refs) {
            const std::string folder = ref.at("folder").get<std::string>();
            json meta;
            const core::Frame whole = joinParts(dirs, folder, meta);
            const fs::path target =
                cached ? staging / "reference_cache" / ref.at("key").get<std::string>()
                       : staging / folder;
            core::writeFrame(whole, target, meta);
            if (cached) core::writeTextFile(target / "key.json", ref.at("what").dump(2) + "\n");
            std::printf(
                "%s: %zu tiles joined -> %s\n", label(ref).c_str(), dirs.size(),
                (cached ? out / "reference_cache" / ref.at("key").get<std::string>() : out / folder)
                    .c_str());
        }
    });
    std::fflush(stdout);
    if (run) return runSuite(*run);
    if (sweep) return runSweep(*sweep);
    return ExitCode::Pass;
}

}  // namespace twinrender::app
