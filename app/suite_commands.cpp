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
#include "app/reference_tiles.h"
#include "app/sequence_run.h"
#include "app/shard.h"
#include "app/test_images.h"
#include "app/test_renderers.h"
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

// The name a test renderer's frames and times carry: "realtime", or "external" for a command or
// images of one's own.
std::string timedRenderer(const std::string& test) {
    return test == "realtime" ? "realtime" : "external";
}

// A row of the run's table on the terminal: a scene's (or a test renderer's) main metrics.
void printSceneRow(const std::string& name, compare::Status status,
                   const compare::MetricValues& metrics, const std::string& test) {
    auto m = [&](const std::string& k) {
        const auto it = metrics.find(k);
        return it == metrics.end() ? std::string("-") : compare::formatValue(it->second);
    };
    auto ms = [&](const std::string& k) {  // "-" for a time not measured (images without one)
        const std::string v = m(k);
        return v == "-" ? v : v + " ms";
    };
    const std::string testTime = "time." + timedRenderer(test) + "_ms";
    const auto rt = metrics.find(testTime), ref = metrics.find("time.raymarch_ms");
    const std::string speed = rt != metrics.end() && ref != metrics.end() && rt->second > 0
                                  ? fmt::format("{:.1f}x", ref->second / rt->second)
                                  : "-";
    std::printf("%-14s %-5s %8s %8s %8s %9s %11s %11s %7s\n", name.c_str(),
                std::string(compare::toString(status)).c_str(), m("beauty.flip").c_str(),
                m("beauty.ssim").c_str(), m("normal.mean_deg").c_str(), m("coverage.iou").c_str(),
                ms(testTime).c_str(), ms("time.raymarch_ms").c_str(), speed.c_str());
}

// The report of a scene that could not be rendered or compared: it fails, saying why.
report::SceneReport errorReport(const LoadedScene& s, const std::string& error) {
    report::SceneReport report;
    report.name = s.scene.name;
    report.description = s.scene.description;
    report.settings = {{"scene_file", s.scene.file.string()}};
    report.error = error;
    return report;
}

// The scene measured by one test renderer (`how.test`), its files in `dir`: a still scene
// against `ref`, a sequence frame by frame with its references from the cache. A renderer that
// cannot render or be compared fails the scene with its error; the other renderers still run.
report::SceneReport measureScene(LoadedScene& s, const core::Frame* ref, const SequenceRun& how,
                                 Devices& devices, ReferenceCache& cache, const fs::path& dir) {
    try {
        if (s.scene.sequence) return runSequence(s, devices, cache, how, dir);
        const core::Frame test = render(how.test, devices, s, &ref->image);
        writeRender(s, test, dir);
        return compareScene(s, *ref, test, how.bounds, how.baseline, how.ppd, how.flipOver, dir);
    } catch (const core::OutputError&) {
        throw;
    } catch (const std::exception& e) {
        return errorReport(s, e.what());
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

std::vector<fs::path> runSceneFiles(const RunOptions& o) {
    return sceneFiles(o.inputs.empty() ? std::vector<std::string>{defaultScenesDir().string()}
                                       : o.inputs);
}

ExitCode runSuite(const RunOptions& o) {
    const bool tty = isatty(STDERR_FILENO);
    if (!o.tiles.empty()) refuseTilesWith("run", "the scenes", !o.shard.empty(), !o.cache.empty());
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
    const std::vector<fs::path> files = runSceneFiles(o);
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

    std::optional<core::FramePart> tiles;
    if (!o.tiles.empty()) tiles = parseTiles(o.tiles);
    // A sequence's video needs ffmpeg: bad environment, said before the first render (of the
    // merge, for tiles).
    for (std::size_t i = 0; i < scenes.size() && !tiles; ++i)
        if (selected[i] && scenes[i].scene.sequence) {
            requireFfmpeg();
            break;
        }
    // The GL context before the first render: without one, nothing can be compared.
    Devices devices(o.requireGpu, {.force = o.selfCheck, .cache = o.cache});
    // The test renderers, and the scenes of those with settings of their own.
    std::vector<TestRendererSpec> specs;
    std::vector<std::vector<LoadedScene>> variants(o.tests.size());
    for (std::size_t k = 0; k < o.tests.size(); ++k) {
        if (std::find(o.tests.begin(), o.tests.begin() + k, o.tests[k]) != o.tests.begin() + k)
            throw core::InputError(fmt::format(
                "--test {} is given twice; each renderer is measured once", o.tests[k]));
        specs.push_back(parseTestRenderer(o.tests[k]));
        std::vector<std::string> sets = o.sets;
        sets.insert(sets.end(), specs[k].overrides.begin(), specs[k].overrides.end());
        if (!specs[k].overrides.empty())
            for (const auto& f : files) variants[k].push_back(loadScene(f, sets));
    }
    // The scene the k-th test renderer renders: the run's, or its own settings'.
    const auto sceneFor = [&](std::size_t k, std::size_t i) -> LoadedScene& {
        return variants[k].empty() ? scenes[i] : variants[k][i];
    };
    const auto tests = [&](const char* name) {
        return std::any_of(specs.begin(), specs.end(),
                           [&](const TestRendererSpec& t) { return t.renderer == name; });
    };
    if (tests("external") || tests("images")) {
        ExternalSettings external = o.external;
        external.root = o.out;
        devices.setExternal(std::move(external));
        // Every image a user rendered earlier is there and sound before the first render.
        if (tests("images"))
            for (std::size_t i = 0; i < scenes.size(); ++i)
                if (selected[i]) checkTestImages(o.external.images, scenes[i]);
    }
    // Tiles of the references: the merge renders and compares the rest.
    if (tiles) return runTiles(scenes, *tiles, o, thresholdsFile);
    if (tests("realtime")) devices.realtime();
    // Sequences take their references from the cache, frame by frame; with --cache, every
    // scene does.
    const fs::path cacheDir =
        o.cache.empty() ? fs::path(o.out) / "reference_cache" : fs::path(o.cache);
    if (!o.cache.empty()) prepareOutputFolder(cacheDir);
    ReferenceCache cache(cacheDir, devices);
    // Making a real-time renderer compiles a user's surface shader: one that does not compile
    // is bad input, said before the first render.
    for (std::size_t i = 0; i < scenes.size(); ++i)
        for (std::size_t k = 0; k < specs.size(); ++k)
            if (selected[i]) makeRenderer(specs[k].renderer, devices, sceneFor(k, i));
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
            // A still scene's reference once, for every test renderer.
            std::optional<core::Frame> ref;
            if (!s.scene.sequence) {
                ref = o.cache.empty() ? render("raymarch", devices, s) : [&] {
                    const auto [key, what] = referenceKey(s, o.sets);
                    core::Frame cached = cache.get(s, key, what);
                    cache.forget(key);
                    return cached;
                }();
                writeRender(s, *ref, dir);
            }
            std::vector<report::SceneReport> reports;
            for (std::size_t k = 0; k < o.tests.size(); ++k) {
                const SequenceRun how{o.sets, bounds[i],  k == 0 && baseline ? &*baseline : nullptr,
                                      o.ppd,  o.flipOver, specs[k].renderer};
                reports.push_back(measureScene(sceneFor(k, i), ref ? &*ref : nullptr, how, devices,
                                               cache, dir / testRendererFolder(o.tests, k)));
            }
            report = joinTestRenderers(std::move(reports), o.tests);
        } catch (const core::OutputError&) {
            throw;  // every later write would fail alike
        } catch (const std::exception& e) {
            // One scene whose reference cannot be rendered fails; the others still run.
            report = errorReport(s, e.what());
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
        nlohmann::json settings = {
            {"scenes", files},          {"sets", o.sets}, {"thresholds", thresholdsFile},
            {"baseline", o.baseline},   {"ppd", o.ppd},   {"flip_over", o.flipOver},
            {"junit", !o.junit.empty()}};
        // The renderers measured: shards of one run measure the same ones.
        settings["tests"] = o.tests;
        if (o.tests != std::vector<std::string>{"realtime"})
            settings["external"] = {{"command", o.external.command},
                                    {"images", o.external.images.string()}};
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

    // One screen: a row per scene (and per test renderer beside the first). printf pads bytes,
    // not columns: the widths of the two headers with multi-byte characters are widened by
    // their extra bytes (ꟻ 3, ° 2).
    std::printf("%-14s %-5s %10s %8s %9s %9s %10s %10s %7s\n", "scene", "", "ꟻLIP", "SSIM",
                "normal°", "cov. IoU", timedRenderer(specs.front().renderer).c_str(), "reference",
                "speed");
    for (const auto& r : run.scenes) {
        printSceneRow(r.name, r.status(), r.metrics, specs.front().renderer);
        for (std::size_t k = 1; k < r.tests.size(); ++k) {
            const report::TestRendererReport& t = r.tests[k];
            const compare::Status st =
                t.error.empty() ? compare::overallStatus(t.checks) : compare::Status::Fail;
            printSceneRow("  + " + t.name, st, t.metrics, t.name.substr(0, t.name.find(':')));
        }
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
