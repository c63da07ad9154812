// twinrender: renders a particle scene with a real-time renderer and a reference raymarcher
// and measures how far the first is from the second. Exit codes: app/exit_code.h.
#include <fmt/format.h>
#include <malloc.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <sstream>

#include "app/doctor_command.h"
#include "app/exit_code.h"
#include "app/export_command.h"
#include "app/interruption.h"
#include "app/merge_command.h"
#include "app/output_folder.h"
#include "app/reference_tiles.h"
#include "app/render_job.h"
#include "app/sequence_run.h"
#include "app/shard.h"
#include "app/studies.h"
#include "app/study_command.h"
#include "app/suite_commands.h"
#include "app/sweep_command.h"
#include "core/cancellation.h"
#include "core/error.h"
#include "core/write_roots.h"

namespace tr = twinrender;
using tr::app::ExitCode;
using tr::app::exitStatus;

namespace {

struct CommonOptions {
    std::vector<std::string> sets;
    int threads = 0;  // 0: every core
    std::string out = "out";
    bool requireGpu = false;
    bool selfCheck = false;
};

void addCommon(CLI::App* cmd, CommonOptions& o) {
    cmd->add_option("--set", o.sets, "KEY=VALUE with the scene's dotted keys (repeatable)")
        ->type_name("KEY=VALUE");
    cmd->add_option("--threads", o.threads, "worker threads (default: every core)")
        ->check(CLI::Range(0, 1024));
    cmd->add_option("--out", o.out, "output folder")->capture_default_str();
    cmd->add_flag("--require-gpu", o.requireGpu,
                  "refuse to run the real-time renderer on a software rasteriser");
    cmd->add_flag("--self-check", o.selfCheck,
                  "run the per-set self-check (both per-set paths, compared) before the first "
                  "real-time frame on any device, llvmpipe too, and not from --cache; where they "
                  "disagree the real-time renderer runs its per-set work on the CPU and says so");
}

// ꟻLIP's viewing condition, for the commands that compare.
void addPpd(CLI::App* cmd, double& ppd) {
    cmd->add_option("--ppd", ppd, "ꟻLIP pixels per degree")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
}

// CI annotations of the checks that did not pass, for the commands that write a run's report.
void addAnnotations(CLI::App* cmd, std::string& format) {
    cmd->add_option("--annotations", format,
                    "print the failures and warnings as CI annotations: github (the default when "
                    "GITHUB_ACTIONS=true) | none")
        ->check(CLI::IsMember({"github", "none"}))
        ->type_name("github|none");
}

// The ꟻLIP error level of beauty.flip_over, for the commands that compare.
void addFlipOver(CLI::App* cmd, double& level) {
    cmd->add_option("--flip-over", level,
                    "ꟻLIP error above which a pixel counts in beauty.flip_over, in (0, 1)")
        ->check(CLI::Validator(
            [](std::string& text) {
                const double v = std::strtod(text.c_str(), nullptr);
                return v > 0.0 && v < 1.0 ? std::string()
                                          : "must be a number between 0 and 1 (exclusive)";
            },
            "(0, 1)"))
        ->capture_default_str();
}

void printRender(const tr::app::LoadedScene& s, const tr::core::Frame& f,
                 const std::filesystem::path& dir) {
    std::printf("%s: %s %dx%d, %zu particles, %.1f ms on %s -> %s\n", s.scene.name.c_str(),
                f.renderer.c_str(), f.image.width(), f.image.height(), f.particleCount,
                f.timingsMs.at("total"), f.device.c_str(), (dir / (f.renderer + ".exr")).c_str());
    const auto unresolved = f.counters.find("unbracketed_rays");
    if (unresolved != f.counters.end() && unresolved->second > 0)
        std::printf("%s: %.0f rays could not be resolved (counted in %s.json)\n",
                    s.scene.name.c_str(), unresolved->second, f.renderer.c_str());
}

// `render --tiles K/N`: the raymarcher's part of the frame (app/reference_tiles.h). The
// real-time, external and "both" renderers draw whole frames only: a part of theirs costs the
// whole frame's passes, so it is refused rather than rendered whole.
ExitCode runRenderTiles(const std::string& scenePath, const std::string& renderer,
                        bool rendererGiven, const std::string& frames, const std::string& tiles,
                        const CommonOptions& o, const std::string& commandLine) {
    const tr::core::FramePart part = tr::app::parseTiles(tiles);
    if (rendererGiven && renderer != "raymarch")
        throw tr::core::InputError(fmt::format(
            "--tiles {} with --renderer {}: only the reference raymarcher renders part of a "
            "frame (--renderer raymarch, the default with --tiles); the real-time renderer "
            "draws whole frames",
            tiles, renderer));
    std::vector<std::string> sets = o.sets;
    if (!frames.empty()) {
        const auto range = tr::app::framesOverrides(frames);
        sets.insert(sets.end(), range.begin(), range.end());
    }
    auto loaded = tr::app::loadScene(scenePath, sets);
    const nlohmann::json settings = {{"scene", scenePath}, {"sets", o.sets}, {"frames", frames}};
    tr::app::renderTiles(loaded, part, !frames.empty(), sets, settings, commandLine, o.out);
    return ExitCode::Pass;
}

ExitCode runRender(const std::string& scenePath, const std::string& renderer,
                   const std::string& frames, const CommonOptions& o,
                   tr::app::ExternalSettings external) {
    std::vector<std::string> sets = o.sets;
    if (!frames.empty()) {
        const auto range = tr::app::framesOverrides(frames);
        sets.insert(sets.end(), range.begin(), range.end());
    }
    auto loaded = tr::app::loadScene(scenePath, sets);
    const std::filesystem::path dir = std::filesystem::path(o.out) / loaded.scene.name;
    const std::vector<std::string> names =
        renderer == "both" ? tr::app::rendererNames() : std::vector<std::string>{renderer};
    // Every renderer first: without a GL context there is nothing to render in real time, and
    // the error should come before minutes of raymarching.
    tr::app::Devices devices(o.requireGpu, {.force = o.selfCheck});
    if (renderer == "external") {
        external.root = o.out;
        devices.setExternal(std::move(external));
    }
    if (!frames.empty()) {
        if (std::find(names.begin(), names.end(), "realtime") != names.end())
            devices.realtimeFor(loaded);
        tr::app::renderFrames(loaded, names, devices, dir);
        return ExitCode::Pass;
    }
    std::vector<std::unique_ptr<tr::core::Renderer>> renderers;
    for (const auto& name : names)
        renderers.push_back(tr::app::makeRenderer(name, devices, loaded));
    tr::app::prepareOutputFolder(dir);
    for (std::size_t i = 0; i < names.size(); ++i) {
        const tr::core::Frame frame = tr::app::render(*renderers[i], names[i], loaded);
        tr::app::writeRender(loaded, frame, dir);
        printRender(loaded, frame, dir);
    }
    return ExitCode::Pass;
}

}  // namespace

int main(int argc, char** argv) {
    // Large buffers (images, ꟻLIP's planes, tens of MB each) from the heap, and freed ones kept
    // for the next: by default glibc maps each afresh and the kernel faults in and zeroes every
    // page again (a third of the CPU time of `compare` on a 1080p PNG pair went to page
    // faults). Up to 512 MiB stays with the process between uses.
    mallopt(M_MMAP_THRESHOLD, 512 << 20);
    mallopt(M_TRIM_THRESHOLD, 512 << 20);
    CLI::App app{"twinrender: a real-time particle renderer measured against an exact reference"};
    app.require_subcommand(1);

    CommonOptions renderOpts;
    std::string scenePath, rendererName = "both", renderFrames;
    auto* render = app.add_subcommand("render", "render one scene");
    render->add_option("SCENE", scenePath, "scene file (.toml)")->required();
    render
        ->add_option("--renderer", rendererName,
                     "realtime | raymarch | both | external (--external-command)")
        ->check(CLI::IsMember({"realtime", "raymarch", "both", "external"}))
        ->capture_default_str();
    tr::app::ExternalSettings renderExternal;
    render->add_option("--external-command", renderExternal.command,
                       "--renderer external: the command run once per frame with the request's "
                       "path (docs/external.md)");
    render
        ->add_option("--external-timeout", renderExternal.timeoutSeconds,
                     "--renderer external: seconds a frame may take")
        ->capture_default_str();
    render
        ->add_option("--frames", renderFrames,
                     "FIRST:LAST[:STEP]: render these frames of the scene's sequence, each into "
                     "OUT/<scene>/<frame>/")
        ->type_name("A:B");
    std::string renderTiles;
    render
        ->add_option("--tiles", renderTiles,
                     "K/N: render part K of N of the frame (rows of tiles) with the raymarcher; "
                     "join the N parts with `merge`")
        ->type_name("K/N");
    addCommon(render, renderOpts);

    tr::app::CompareOptions compareOpts;
    auto* compareCmd =
        app.add_subcommand("compare", "compare two images (AOV EXRs, or plain images)");
    compareCmd->add_option("REF", compareOpts.reference, "reference image")->required();
    compareCmd->add_option("TEST", compareOpts.test, "image to measure")->required();
    compareCmd->add_option("--out", compareOpts.out, "output folder")->capture_default_str();
    compareCmd->add_option("--thresholds", compareOpts.thresholds, "thresholds file (TOML)");
    compareCmd->add_option("--scene", compareOpts.scene,
                           "the scene the images show: its exposure and light direction");
    compareCmd->add_option("--set", compareOpts.sets, "KEY=VALUE overrides of that scene")
        ->type_name("KEY=VALUE");
    addPpd(compareCmd, compareOpts.ppd);
    addFlipOver(compareCmd, compareOpts.flipOver);

    tr::app::DoctorOptions doctorOpts;
    auto* doctorCmd = app.add_subcommand(
        "doctor",
        "check this machine: GL device and limits, every program variant, the per-set self-check");
    doctorCmd->add_option("--scene", doctorOpts.scene, "the self-check's scene")
        ->capture_default_str();
    doctorCmd->add_option("--set", doctorOpts.sets, "KEY=VALUE overrides of that scene")
        ->type_name("KEY=VALUE");
    doctorCmd->add_flag("--require-gpu", doctorOpts.requireGpu,
                        "fail when the GL device is a software rasteriser");

    tr::app::RunOptions runOpts;
    CommonOptions runCommon;
    auto* runCmd = app.add_subcommand(
        "run", "render every scene with both renderers, compare, and write the report");
    runCmd->add_option("SCENES", runOpts.inputs, "scene files or folders (default: scenes/)");
    runCmd->add_option("--thresholds", runOpts.thresholds,
                       "thresholds file (default: thresholds.toml beside the scenes)");
    runCmd->add_option("--baseline", runOpts.baseline, "baseline from `twinrender bless`");
    runCmd->add_option("--junit", runOpts.junit, "also write JUnit XML here");
    runCmd->add_option("--cache", runOpts.cache,
                       "reference cache folder for every scene and --studies (default: "
                       "sequences only, in OUT/reference_cache)");
    addPpd(runCmd, runOpts.ppd);
    addFlipOver(runCmd, runOpts.flipOver);
    std::vector<std::string> runTests;
    runCmd
        ->add_option("--test", runTests,
                     "the renderer measured: realtime (built in, the default), "
                     "realtime:KEY=VALUE,... (with settings of its own) or external "
                     "(--external-command); repeatable, side by side")
        ->check(CLI::Validator(
            [](std::string& text) {
                return text == "realtime" || text == "external" || text.rfind("realtime:", 0) == 0
                           ? std::string()
                           : "must be realtime, realtime:KEY=VALUE,... or external";
            },
            "TEST"))
        ->type_name("realtime|realtime:KEY=VALUE,...|external");
    std::string runTestImages;
    runCmd
        ->add_option("--test-images", runTestImages,
                     "measure images rendered earlier, DIR/<scene>/<frame>.exr, as an external "
                     "renderer's (docs/external.md); after any --test")
        ->type_name("DIR");
    runCmd->add_option("--external-command", runOpts.external.command,
                       "--test external: the command run once per frame with the request's path "
                       "(docs/external.md)");
    runCmd
        ->add_option("--external-timeout", runOpts.external.timeoutSeconds,
                     "--test external: seconds a frame may take")
        ->capture_default_str();
    runCmd
        ->add_option(
            "--shard", runOpts.shard,
            "K/N: run every N-th scene (sorted by name) starting at the K-th; join with `merge`")
        ->type_name("K/N");
    runCmd
        ->add_option("--tiles", runOpts.tiles,
                     "K/N: render part K of N of every scene's reference and nothing else; "
                     "`merge` joins the N parts and runs the run")
        ->type_name("K/N");
    addAnnotations(runCmd, runOpts.annotations);
    std::string runStudies;
    runCmd
        ->add_option(
            "--studies", runStudies,
            "also run the stability studies into OUT/studies, linked from the report: quick | "
            "full, every study, or quick:NAME,... | full:NAME,..., the studies named")
        ->check([](const std::string& v) -> std::string {
            const std::string mode = v.substr(0, v.find(':'));
            if (mode == "quick" || mode == "full") return "";
            return "--studies: \"" + v +
                   "\" is neither quick nor full (quick, full, quick:NAME,...)";
        })
        ->type_name("quick|full[:NAME,...]");
    addCommon(runCmd, runCommon);

    tr::app::SweepOptions sweepOpts;
    CommonOptions sweepCommon;
    sweepCommon.out = "out/sweep";
    auto* sweepCmd = app.add_subcommand(
        "sweep", "time against error over the cartesian product of varied settings");
    sweepCmd->add_option("SCENE", sweepOpts.scene, "scene file (.toml)")->required();
    sweepCmd
        ->add_option(
            "--vary", sweepOpts.vary,
            "KEY=V1,V2,... with the scene's dotted keys (repeatable; realtime.* or raymarch.*)")
        ->type_name("KEY=V1,V2,...")
        ->required();
    sweepCmd->add_option("--metric", sweepOpts.metric, "the chart's error metric")
        ->capture_default_str();
    sweepCmd
        ->add_option(
            "--frames", sweepOpts.frames,
            "frames per combination, timed as their median (default 5; 1 when varying raymarch.*)")
        ->check(CLI::Range(1, 1000));
    sweepCmd->add_option("--thresholds", sweepOpts.thresholds,
                         "thresholds file (TOML): mark the combinations that pass and name the "
                         "cheapest");
    sweepCmd->add_option("--cache", sweepOpts.cache,
                         "reference cache folder (default: OUT/reference_cache)");
    addPpd(sweepCmd, sweepOpts.ppd);
    addFlipOver(sweepCmd, sweepOpts.flipOver);
    sweepCmd
        ->add_option("--shard", sweepOpts.shard,
                     "K/N: every N-th combination starting at the K-th; join with `merge`")
        ->type_name("K/N");
    sweepCmd
        ->add_option("--tiles", sweepOpts.tiles,
                     "K/N: render part K of N of every reference the sweep takes and nothing "
                     "else; `merge` joins the N parts and runs the sweep")
        ->type_name("K/N");
    addCommon(sweepCmd, sweepCommon);

    tr::app::StudyOptions studyOpts;
    CommonOptions studyCommon;
    studyCommon.out = "out/studies";
    auto* studyCmd = app.add_subcommand("study", "studies: " + tr::app::studyNames());
    studyCmd->add_option("NAMES", studyOpts.names,
                         "studies to run (default: all): " + tr::app::studyNames());
    studyCmd->add_flag("--quick", studyOpts.quick,
                       "fewer points and particles (seconds per study)");
    studyCmd->add_option("--cache", studyOpts.cache,
                         "reference cache folder (default: OUT/reference_cache)");
    addPpd(studyCmd, studyOpts.ppd);
    addCommon(studyCmd, studyCommon);

    tr::app::MergeOptions mergeOpts;
    auto* mergeCmd = app.add_subcommand("merge",
                                        "join the output folders of `run|sweep --shard K/N` or "
                                        "`render|run --tiles K/N`");
    mergeCmd->add_option("DIRS", mergeOpts.inputs, "the shards' or tiles' output folders")
        ->required();
    mergeCmd->add_option("--out", mergeOpts.out, "output folder of the joined report")->required();
    addAnnotations(mergeCmd, mergeOpts.annotations);

    tr::app::ExportOptions exportOpts;
    auto* exportCmd = app.add_subcommand(
        "export",
        "write what another renderer needs to draw a scene: particles as PLY, camera, "
        "light, materials with baked textures (docs/external.md)");
    exportCmd->add_option("SCENE", exportOpts.scene, "scene file (.toml)")->required();
    exportCmd->add_option("--out", exportOpts.out, "output folder")->capture_default_str();
    exportCmd->add_option("--set", exportOpts.sets, "KEY=VALUE with the scene's dotted keys")
        ->type_name("KEY=VALUE");
    exportCmd
        ->add_option("--frames", exportOpts.frames,
                     "FIRST:LAST[:STEP]: these frames of the scene's sequence, each into "
                     "OUT/<scene>/<frame>/")
        ->type_name("A:B");

    std::string blessDir, blessOut;
    auto* blessCmd = app.add_subcommand("bless", "write the baseline of a run");
    blessCmd->add_option("RUN_DIR", blessDir, "the output folder of `twinrender run`")->required();
    blessCmd->add_option("--out", blessOut, "baseline file (default: RUN_DIR/baseline.json)");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int rc = app.exit(e);  // 0 after --help
        return exitStatus(rc == 0 ? ExitCode::Pass : ExitCode::BadInput);
    }

    tr::app::installInterruptHandlers();
    try {
        // The only places this process writes: what the user named here, never a place a
        // scene, thresholds file, baseline or manifest names (core/write_roots.h).
        const auto allow = [](const std::string& path) {
            if (!path.empty()) tr::core::allowWritesUnder(path);
        };
        if (*render) allow(renderOpts.out);
        if (*compareCmd) allow(compareOpts.out);
        if (*blessCmd)
            allow(blessOut.empty() ? (std::filesystem::path(blessDir) / "baseline.json").string()
                                   : blessOut);
        if (*runCmd) {
            allow(runCommon.out);
            allow(runOpts.cache);
            allow(runOpts.junit);
        }
        if (*sweepCmd) {
            allow(sweepCommon.out);
            allow(sweepOpts.cache);
        }
        if (*studyCmd) {
            allow(studyCommon.out);
            allow(studyOpts.cache);
        }
        if (*mergeCmd) allow(mergeOpts.out);
        if (*exportCmd) allow(exportOpts.out);
        const int requested = *runCmd     ? runCommon.threads
                              : *sweepCmd ? sweepCommon.threads
                              : *studyCmd ? studyCommon.threads
                                          : renderOpts.threads;
        std::string commandLine;
        for (int i = 0; i < argc; ++i) commandLine += (i ? " " : "") + std::string(argv[i]);
        const int threads = requested > 0 ? requested : tbb::this_task_arena::max_concurrency();
        tbb::task_arena arena(threads);
        ExitCode rc = ExitCode::Pass;
        arena.execute([&] {
            if (*render && !renderTiles.empty())
                rc = runRenderTiles(scenePath, rendererName, render->count("--renderer") > 0,
                                    renderFrames, renderTiles, renderOpts, commandLine);
            else if (*render)
                rc = runRender(scenePath, rendererName, renderFrames, renderOpts, renderExternal);
            if (*doctorCmd) rc = tr::app::runDoctor(doctorOpts);
            if (*compareCmd) rc = tr::app::runCompare(compareOpts);
            if (*exportCmd) rc = tr::app::runExport(exportOpts);
            if (*blessCmd) rc = tr::app::runBless(blessDir, blessOut);
            if (*runCmd) {
                runOpts.out = runCommon.out;
                runOpts.sets = runCommon.sets;
                runOpts.requireGpu = runCommon.requireGpu;
                runOpts.selfCheck = runCommon.selfCheck;
                runOpts.commandLine = commandLine;
                runOpts.linkStudies = !runStudies.empty();
                // --test realtime alone by default; --test-images after any --test.
                runOpts.tests = runTests;
                if (!runTestImages.empty()) {
                    runOpts.tests.push_back("images");
                    runOpts.external.images = runTestImages;
                }
                if (runOpts.tests.empty()) runOpts.tests = {"realtime"};
                if (runOpts.linkStudies && (!runOpts.shard.empty() || !runOpts.tiles.empty()))
                    throw tr::core::InputError(fmt::format(
                        "run --studies with {}: the studies are not split; run them once with "
                        "`twinrender study`",
                        runOpts.shard.empty() ? "--tiles" : "--shard"));
                // quick:NAME,NAME: only those, each checked before the suite renders.
                std::vector<std::string> runStudyNames;
                if (const auto colon = runStudies.find(':'); colon != std::string::npos) {
                    std::stringstream names(runStudies.substr(colon + 1));
                    for (std::string name; std::getline(names, name, ',');) {
                        if (!tr::app::findStudy(name))
                            throw tr::core::InputError(
                                fmt::format("run --studies: no study {}; the studies are {}",
                                            name.empty() ? "\"\"" : name, tr::app::studyNames()));
                        runStudyNames.push_back(name);
                    }
                }
                rc = tr::app::runSuite(runOpts);
                if (!runStudies.empty()) {
                    // The study scenes are not the suite's: the run's --set does not apply.
                    tr::app::StudyOptions so;
                    so.out = (std::filesystem::path(runCommon.out) / "studies").string();
                    so.quick = runStudies.starts_with("quick");
                    so.names = runStudyNames;
                    so.requireGpu = runCommon.requireGpu;
                    so.selfCheck = runCommon.selfCheck;
                    so.ppd = runOpts.ppd;
                    // One reference cache for the suite and its studies (scripts/run keeps it
                    // across runs).
                    so.cache = runOpts.cache;
                    so.commandLine = commandLine;
                    so.back = "../index.html";
                    rc = std::max(rc, tr::app::runStudies(so));
                }
            }
            if (*sweepCmd) {
                sweepOpts.out = sweepCommon.out;
                sweepOpts.sets = sweepCommon.sets;
                sweepOpts.requireGpu = sweepCommon.requireGpu;
                sweepOpts.selfCheck = sweepCommon.selfCheck;
                sweepOpts.commandLine = commandLine;
                rc = tr::app::runSweep(sweepOpts);
            }
            if (*studyCmd) {
                studyOpts.out = studyCommon.out;
                studyOpts.sets = studyCommon.sets;
                studyOpts.requireGpu = studyCommon.requireGpu;
                studyOpts.selfCheck = studyCommon.selfCheck;
                studyOpts.commandLine = commandLine;
                rc = tr::app::runStudies(studyOpts);
            }
            if (*mergeCmd) {
                mergeOpts.commandLine = commandLine;
                rc = tr::app::runMerge(mergeOpts);
            }
        });
        return exitStatus(rc);
    } catch (const tr::core::Cancelled&) {
        const int signal = tr::app::interruptSignal();
        const char* name = sigabbrev_np(signal);
        std::fprintf(stderr, "\nstopped by SIG%s: no report written, no temporary file left\n",
                     name ? name : "?");
        return 128 + signal;
    } catch (const tr::core::InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return exitStatus(ExitCode::BadInput);
    } catch (const tr::core::NotComparableError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return exitStatus(ExitCode::NotComparable);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return exitStatus(ExitCode::BadInput);
    }
}
