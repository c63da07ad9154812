#include "app/suite_commands.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <map>
#include <string_view>

#include "app/comparison.h"
#include "app/interruption.h"
#include "app/output_folder.h"
#include "app/progress.h"
#include "app/reference_cache.h"
#include "app/sequence_run.h"
#include "app/shard.h"
#include "app/video_encoder.h"
#include "compare/error_maps.h"
#include "compare/metric_table.h"
#include "core/error.h"
#include "core/folder_name.h"
#include "core/image_io.h"
#include "core/install_layout.h"
#include "report/annotations.h"
#include "report/junit.h"
#include "report/report_json.h"

namespace twinrender::app {

namespace fs = std::filesystem;

namespace {

// The status of a metric's checks, for the terminal table.
std::string statusOf(const std::vector<compare::Check>& checks, const std::string& metric) {
    compare::Status s = compare::Status::Pass;
    bool any = false;
    for (const auto& c : checks)
        if (c.metric == metric) {
            s = compare::worst(s, c.status);
            any = true;
        }
    return any ? std::string(compare::toString(s)) : "";
}

void printMetricTable(const compare::MetricValues& metrics,
                      const std::vector<compare::Check>& checks,
                      const std::vector<std::string>& notProvided = {}) {
    std::printf("%-24s %14s  %-4s %s\n", "metric", "value", "unit", "check");
    for (const auto& [name, value] : metrics)
        std::printf("%-24s %14s  %-4s %s\n", name.c_str(), compare::formatValue(value).c_str(),
                    compare::metricUnit(name).c_str(), statusOf(checks, name).c_str());
    for (const std::string& name : notProvided)
        std::printf("%-24s %14s  %-4s %s\n", name.c_str(), "not provided",
                    compare::metricUnit(name).c_str(), "-");
    for (const auto& c : checks)
        if (c.status != compare::Status::Pass)
            std::printf("  %s: %s\n", std::string(compare::toString(c.status)).c_str(),
                        c.message.c_str());
}

// The scene files of the inputs: files as given, folders by their *.toml (sorted), except
// thresholds.toml, which is not a scene.
std::vector<fs::path> sceneFiles(const std::vector<std::string>& inputs) {
    std::vector<fs::path> files;
    for (const auto& in : inputs) {
        const fs::path p(in);
        if (fs::is_directory(p)) {
            std::vector<fs::path> found;
            for (const auto& e : fs::directory_iterator(p))
                if (e.path().extension() == ".toml" && e.path().filename() != "thresholds.toml")
                    found.push_back(e.path());
            std::sort(found.begin(), found.end());
            if (found.empty())
                throw core::InputError(
                    fmt::format("{}: the folder holds no scene (.toml) files", in));
            files.insert(files.end(), found.begin(), found.end());
        } else if (fs::is_regular_file(p)) {
            files.push_back(p);
        } else {
            throw core::InputError(fmt::format("{}: no such scene file or folder", in));
        }
    }
    return files;
}

fs::path defaultScenesDir() {
    if (fs::is_directory("scenes")) return "scenes";
    return core::resourceDir() / "scenes";
}

// What `run` writes beside the scenes' folders, which no scene's folder may take.
constexpr std::array<std::string_view, 8> kRunFiles = {
    "index.html", "summary.json", "summary.md",      "junit.xml",
    "shard.json", "studies",      "reference_cache", "baseline.json"};

// Every scene has a folder of its own in the run's output folder: two names that one folder
// would hold (equal, or equal but for case on macOS and Windows), or a name the run's own
// files take, are bad input before anything renders.
void checkSceneFolders(const std::vector<LoadedScene>& scenes) {
    std::map<std::string, const core::Scene*> byKey;
    for (const LoadedScene& s : scenes) {
        const std::string key = core::folderNameKey(s.scene.name);
        for (std::string_view f : kRunFiles)
            if (key == f)
                throw core::InputError(fmt::format(
                    "{}: the scene name '{}' is the name of a file or folder the run writes "
                    "beside the scenes' folders ({}); rename the scene",
                    s.scene.file.string(), s.scene.name, fmt::join(kRunFiles, ", ")));
        const auto [it, added] = byKey.emplace(key, &s.scene);
        if (!added)
            throw core::InputError(fmt::format(
                "{} and {} are named '{}' and '{}', which name one output folder (on macOS and "
                "Windows, names differing only in case do too); give the scenes names that "
                "differ",
                it->second->file.string(), s.scene.file.string(), it->second->name, s.scene.name));
    }
}

}  // namespace

ExitCode runCompare(const CompareOptions& o) {
    // The scene first: its exposure and light, as `run` measures its frames.
    compare::MetricSettings settings;
    settings.ppd = o.ppd;
    settings.flipOver = o.flipOver;
    if (!o.scene.empty()) settings = metricSettings(loadScene(o.scene, o.sets), o.ppd, o.flipOver);
    const auto [ref, test] = core::readImages(o.reference, o.test);
    const compare::MetricResult result = compare::computeMetrics(ref, test, settings);
    report::SceneReport report;
    report.name = fs::path(o.test).stem().string();
    report.metrics = result.values;
    report.notProvided = result.notProvided;
    report.notApplicable = result.notApplicable;
    if (!o.thresholds.empty()) {
        compare::Bounds bounds = compare::Thresholds::parseFile(o.thresholds).forScene(report.name);
        // Plain images have beauty metrics only, and an AOV image that lacks a metric's channels
        // does not provide it: bounds on those do not apply (never a pass: listed as not
        // provided).
        if (!compare::isAovImage(ref) || !compare::isAovImage(test))
            bounds = compare::filterBounds(
                bounds, [](const std::string& m) { return compare::computedOnPlainImages(m); });
        bounds = compare::filterBounds(bounds, [&](const std::string& m) {
            return std::find(result.notProvided.begin(), result.notProvided.end(), m) ==
                       result.notProvided.end() &&
                   !result.notApplicable.count(m);
        });
        report.checks = compare::evaluate(report.metrics, bounds);
    }
    const fs::path out(o.out);
    writeTogether(out, [&](const fs::path& staging) {
        report.errorMaps = compare::writeErrorMapImages(result.errorMaps, staging);
        report::writeMetricsJson(report, staging / "metrics.json");
    });
    printMetricTable(report.metrics, report.checks, result.notProvided);
    if (!result.missingChannels.empty())
        std::printf("not provided: the images lack %s\n",
                    fmt::format("{}", fmt::join(result.missingChannels, ", ")).c_str());
    if (result.hdrExposures)
        std::printf("beauty.hdrflip over %d exposures from %.3f to %.3f stops\n",
                    result.hdrExposures->count, result.hdrExposures->start,
                    result.hdrExposures->stop);
    const compare::Status status = report.status();
    std::printf("%s -> %s (%s)\n", o.test.c_str(), (out / "metrics.json").c_str(),
                std::string(compare::toString(status)).c_str());
    return exitCodeOf(status);
}

ExitCode runSuite(const RunOptions& o) {
    const bool tty = isatty(STDERR_FILENO);
    // Everything is read and checked before the first render.
    std::vector<std::string> inputs = o.inputs;
    if (inputs.empty()) inputs.push_back(defaultScenesDir().string());
    // Without --thresholds, the thresholds.toml beside the scenes (the first input's folder),
    // so `run scenes/planet.toml` is held to the same bounds as the whole suite.
    std::string thresholdsFile = o.thresholds;
    if (thresholdsFile.empty()) {
        const fs::path first(inputs.front());
        const fs::path dir = fs::is_directory(first) ? first : first.parent_path();
        if (fs::is_regular_file(dir / "thresholds.toml"))
            thresholdsFile = (dir / "thresholds.toml").string();
    }
    const std::vector<fs::path> files = sceneFiles(inputs);
    std::vector<LoadedScene> scenes;
    for (const auto& f : files) scenes.push_back(loadScene(f, o.sets));
    checkSceneFolders(scenes);
    const compare::Thresholds thresholds = thresholdsFile.empty()
                                               ? compare::Thresholds::parseString("", "(none)")
                                               : compare::Thresholds::parseFile(thresholdsFile);
    std::vector<compare::Bounds> bounds;
    for (const auto& s : scenes)
        bounds.push_back(thresholds.forScene(s.scene.name, &s.scene.compare));
    std::optional<compare::Baseline> baseline;
    if (!o.baseline.empty()) baseline = compare::readBaseline(o.baseline);
    // A shard runs every N-th scene of the suite sorted by name, starting at the (K-1)-th.
    std::optional<Shard> shard;
    if (!o.shard.empty()) shard = parseShard(o.shard);
    std::vector<bool> selected(scenes.size(), true);
    if (shard) {
        std::vector<std::size_t> byName(scenes.size());
        for (std::size_t i = 0; i < byName.size(); ++i) byName[i] = i;
        std::sort(byName.begin(), byName.end(), [&](std::size_t a, std::size_t b) {
            return scenes[a].scene.name < scenes[b].scene.name;
        });
        for (std::size_t p = 0; p < byName.size(); ++p) selected[byName[p]] = shard->takes(p);
    }

    // A sequence's video needs ffmpeg: bad environment, said before the first render.
    for (std::size_t i = 0; i < scenes.size(); ++i)
        if (selected[i] && scenes[i].scene.sequence) {
            requireFfmpeg();
            break;
        }
    // The GL context before the first render: without one, nothing can be compared.
    Devices devices(o.requireGpu, {.force = o.selfCheck, .cache = o.cache});
    if (o.test == "external") {
        for (std::size_t i = 0; i < scenes.size(); ++i)
            if (selected[i] && scenes[i].scene.sequence)
                throw core::InputError(fmt::format(
                    "{}: run --test external measures still scenes; the scene is a sequence "
                    "(render its frames with `render --renderer external --frames A:B` and "
                    "compare them)",
                    scenes[i].scene.file.string()));
        ExternalSettings external = o.external;
        external.root = o.out;
        devices.setExternal(std::move(external));
    } else {
        devices.realtime();
    }
    // Sequences take their references from the cache, frame by frame; with --cache, every
    // scene does.
    const fs::path cacheDir =
        o.cache.empty() ? fs::path(o.out) / "reference_cache" : fs::path(o.cache);
    if (!o.cache.empty()) prepareOutputFolder(cacheDir);
    ReferenceCache cache(cacheDir, devices);
    // Making a real-time renderer compiles a user's surface shader: one that does not compile
    // is bad input, said before the first render.
    for (std::size_t i = 0; i < scenes.size(); ++i)
        if (selected[i]) makeRenderer(o.test, devices, scenes[i]);
    const fs::path out(o.out);
    prepareOutputFolder(out);

    report::RunReport run;
    run.createdAt = nowUtc();
    run.commandLine = o.commandLine;
    run.thresholdsFile = thresholdsFile;
    run.baselineFile = o.baseline;
    const std::size_t count =
        static_cast<std::size_t>(std::count(selected.begin(), selected.end(), true));
    using Clock = std::chrono::steady_clock;
    const auto started = Clock::now();
    for (std::size_t i = 0, done = 0; i < scenes.size(); ++i) {
        if (!selected[i]) continue;
        LoadedScene& s = scenes[i];
        const fs::path dir = out / s.scene.name;
        if (tty) {
            // What remains of the main job: the scenes at the pace of those done so far, then
            // the studies (which count their own points down).
            const double elapsed = std::chrono::duration<double>(Clock::now() - started).count();
            const std::string left =
                done == 0 ? ""
                          : fmt::format(", about {:.0f} s left", elapsed / done * (count - done));
            std::fprintf(stderr, "[%zu/%zu scenes%s%s] %s\n", done + 1, count, left.c_str(),
                         o.linkStudies ? ", then the studies" : "", s.scene.name.c_str());
        }
        ++done;
        report::SceneReport report;
        try {
            if (s.scene.sequence) {
                const SequenceRun sequence{o.sets, bounds[i], baseline ? &*baseline : nullptr,
                                           o.ppd, o.flipOver};
                run.scenes.push_back(runSequence(s, devices, cache, sequence, dir));
                continue;
            }
            const core::Frame ref = o.cache.empty() ? render("raymarch", devices, s) : [&] {
                const auto [key, what] = referenceKey(s, o.sets);
                core::Frame cached = cache.get(s, key, what);
                cache.forget(key);
                return cached;
            }();
            writeRender(s, ref, dir);
            const core::Frame test = render(o.test, devices, s, &ref.image);
            writeRender(s, test, dir);
            report = compareScene(s, ref, test, bounds[i], baseline ? &*baseline : nullptr, o.ppd,
                                  o.flipOver, dir);
        } catch (const core::OutputError&) {
            throw;  // every later write would fail alike
        } catch (const std::exception& e) {
            // One scene that cannot be rendered or compared fails; the others still run.
            report = report::SceneReport{};
            report.name = s.scene.name;
            report.description = s.scene.description;
            report.settings = {{"scene_file", s.scene.file.string()}};
            report.error = e.what();
        }
        run.scenes.push_back(std::move(report));
    }
    if (o.linkStudies) run.links.push_back({"stability studies", "studies/index.html"});
    // A signal during the renders leaves no report; one from here on lets it finish.
    throwIfInterrupted();
    nlohmann::json manifest;
    if (shard) {
        // What merge needs to rebuild the whole run's report, and what must be equal across
        // the shards of one run.
        nlohmann::json names = nlohmann::json::array(), files = nlohmann::json::array(),
                       reports = nlohmann::json::array();
        for (const auto& s : scenes) {
            names.push_back(s.scene.name);
            files.push_back(fs::absolute(s.scene.file).lexically_normal().string());
        }
        for (const auto& r : run.scenes) reports.push_back(report::sceneReportJson(r));
        const nlohmann::json settings = {
            {"scenes", files},          {"sets", o.sets}, {"thresholds", thresholdsFile},
            {"baseline", o.baseline},   {"ppd", o.ppd},   {"flip_over", o.flipOver},
            {"junit", !o.junit.empty()}};
        manifest = {{"command", "run"},
                    {"settings", settings},
                    {"scenes", names},
                    {"reports", reports},
                    {"junit", !o.junit.empty()},
                    {"created", run.createdAt},
                    {"command_line", o.commandLine}};
    }
    writeTogether(out, [&](const fs::path& staging) {
        report::writeReport(run, staging);
        if (shard) writeShardManifest(*shard, manifest, staging);
    });
    if (!o.junit.empty()) report::writeJunit(run, o.junit);

    // One screen: a row per scene. printf pads bytes, not columns: the widths of the two
    // headers with multi-byte characters are widened by their extra bytes (ꟻ 3, ° 2).
    std::printf("%-14s %-5s %10s %8s %9s %9s %10s %10s %7s\n", "scene", "", "ꟻLIP", "SSIM",
                "normal°", "cov. IoU", "realtime", "reference", "speed");
    for (const auto& r : run.scenes) {
        auto m = [&](const char* k) {
            const auto it = r.metrics.find(k);
            return it == r.metrics.end() ? std::string("-") : compare::formatValue(it->second);
        };
        const auto rt = r.metrics.find("time.realtime_ms"),
                   ref = r.metrics.find("time.raymarch_ms");
        const std::string speed = rt != r.metrics.end() && ref != r.metrics.end() && rt->second > 0
                                      ? fmt::format("{:.1f}x", ref->second / rt->second)
                                      : "-";
        std::printf("%-14s %-5s %8s %8s %8s %9s %8s ms %8s ms %7s\n", r.name.c_str(),
                    std::string(compare::toString(r.status())).c_str(), m("beauty.flip").c_str(),
                    m("beauty.ssim").c_str(), m("normal.mean_deg").c_str(),
                    m("coverage.iou").c_str(), m("time.realtime_ms").c_str(),
                    m("time.raymarch_ms").c_str(), speed.c_str());
        if (!r.error.empty()) std::printf("  error: %s\n", r.error.c_str());
        for (const auto& c : r.checks)
            if (c.status != compare::Status::Pass)
                std::printf("  %s: %s\n", std::string(compare::toString(c.status)).c_str(),
                            c.message.c_str());
    }
    const compare::Status status = run.status();
    std::printf("%s: %s\n", std::string(compare::toString(status)).c_str(),
                (out / "index.html").c_str());
    printAnnotations(run, o.annotations);
    return exitCodeOf(status);
}

void printAnnotations(const report::RunReport& run, const std::string& format) {
    const char* actions = std::getenv("GITHUB_ACTIONS");
    const bool github =
        format == "github" || (format.empty() && actions && std::string(actions) == "true");
    if (!github) return;
    const char* workspace = std::getenv("GITHUB_WORKSPACE");
    const fs::path root = workspace && *workspace ? fs::path(workspace) : fs::current_path();
    std::fputs(report::githubAnnotations(run, root).c_str(), stdout);
    std::fflush(stdout);
}

ExitCode runBless(const std::string& runDir, const std::string& out) {
    const compare::Baseline b = compare::blessRunDir(runDir);
    const fs::path file = out.empty() ? fs::path(runDir) / "baseline.json" : fs::path(out);
    compare::writeBaseline(b, file);
    std::printf("baseline of %zu scenes -> %s\n", b.scenes.size(), file.c_str());
    return ExitCode::Pass;
}

}  // namespace twinrender::app
