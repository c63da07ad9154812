#include "app/sweep_command.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>

#include "app/comparison.h"
#include "app/interruption.h"
#include "app/output_folder.h"
#include "app/reference_cache.h"
#include "app/reference_tiles.h"
#include "app/render_job.h"
#include "app/sequence_run.h"
#include "app/shard.h"
#include "compare/error_maps.h"
#include "compare/metric_table.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/sequence.h"
#include "core/write_roots.h"
#include "report/report_json.h"
#include "report/sequence_summary.h"
#include "report/study_summary.h"
#include "report/sweep_report.h"

namespace twinrender::app {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The convergence sweep's tight reference: 1e-7 h root accuracy and 16 samples per pixel,
// or tighter when the sweep itself goes beyond them.
constexpr double TIGHT_ROOT_TOLERANCE = 1e-7;
constexpr int TIGHT_SPP = 16;

std::string keyOf(const std::string& assignment) {
    return assignment.substr(0, assignment.find('='));
}

// One combination, loaded and checked before anything renders.
struct Job {
    std::size_t index = 0;
    std::vector<std::string> varied;  // its key=value overrides
    LoadedScene test;
    std::vector<std::string> testOverrides;
    // The reference: in realtime mode the test scene itself (the raymarcher reads its
    // non-realtime part), in raymarch mode the tight scene.
    std::optional<LoadedScene> tight;
    std::vector<std::string> tightOverrides;
    compare::Bounds bounds;  // the scene's, with --thresholds
};

bool anyRowError(const report::SweepReport& report) {
    return std::any_of(report.rows.begin(), report.rows.end(),
                       [](const report::SweepRow& r) { return !r.error.empty(); });
}

// After a combination's line: ", pass", ", warn (smoothness.ratio)" or
// ", fail (normal.mean_deg; warned: normal.p95_deg)"; "" when it is not checked.
std::string verdictSuffix(const report::SweepRow& row) {
    if (!row.status) return "";
    std::string metrics = fmt::format("{}", fmt::join(row.failed, ", "));
    if (!row.warned.empty())
        metrics +=
            fmt::format("{}{}", metrics.empty() ? "" : "; warned: ", fmt::join(row.warned, ", "));
    return fmt::format(", {}{}", compare::toString(*row.status),
                       metrics.empty() ? "" : " (" + metrics + ")");
}

// What a combination measured, beside its row's times and metrics: what its bounds see and
// what its folder shows.
struct Measured {
    core::Frame shown;  // the test render in the folder (a sequence's: its worst frame)
    std::map<std::string, core::Image> flipMap;  // that render's beauty.flip error map
    compare::MetricValues checked;               // the row's metrics and the times
    std::optional<report::SequenceReport> sequence;
};

// The test render's counters as count.* metrics of the row.
void addCounters(const core::Frame& test, compare::MetricValues& metrics) {
    for (const auto& [name, n] : test.counters) metrics["count." + name] = n;
}

// A still scene: the reference, then `frames` timed test renders (the real-time renderer first
// renders one frame untimed: renderTimed), their median times.
Measured measureStill(const Job& job, report::SweepRow& row, const std::string& testRenderer,
                      int frames, const SweepOptions& o, Devices& devices, ReferenceCache& cache) {
    const bool convergence = testRenderer == "raymarch";
    const LoadedScene& refScene = convergence ? *job.tight : job.test;
    const auto [key, what] =
        referenceKey(refScene, convergence ? job.tightOverrides : job.testOverrides);
    row.referenceKey = key;
    const core::Frame& ref = cache.get(refScene, key, what);
    TimedFrame timed = renderTimed(testRenderer, devices, job.test, frames, !convergence,
                                   convergence ? nullptr : &ref.image);
    Measured m;
    m.shown = std::move(timed.frame);
    row.timingsMs = std::move(timed.medianMs);
    const compare::MetricSettings settings = metricSettings(job.test, o.ppd, o.flipOver);
    compare::MetricResult result = compare::computeMetrics(ref.image, m.shown.image, settings);
    addSplitMetrics(ref, m.shown, settings, result.values);
    row.metrics = result.values;
    addCounters(m.shown, row.metrics);
    if (auto it = result.errorMaps.find("beauty.flip"); it != result.errorMaps.end())
        m.flipMap.insert(result.errorMaps.extract(it));
    // What the bounds see, as in `run`: the metrics and the renders' times, the test
    // renderer's being its median frame.
    m.checked = row.metrics;
    addTimeMetrics(ref, m.shown, m.checked);
    m.checked["time." + testRenderer + "_ms"] = row.timingsMs.at("total");
    return m;
}

// A sequence scene, as `run` renders one (compareSequenceFrames): every frame of its range,
// each once, the real-time renderer getting each as a new particle set, so that a frame's time
// includes the per-set work; the reference per frame from the cache. The row holds the
// summary over the frames (report::summariseSequence: each metric at its worst frame, the
// flicker's mean and largest) and each stage's median over the frames; the folder, the frame
// with the largest beauty.flip.
Measured measureSequence(Job& job, report::SweepRow& row, const std::string& testRenderer,
                         const SweepOptions& o, Devices& devices, ReferenceCache& cache) {
    const bool convergence = testRenderer == "raymarch";
    // The shader variants compile on their first use in the driver: one untimed frame by a
    // renderer of its own, so that the sequence's renderer still sees its first frame as a new
    // particle set.
    if (!convergence) render(testRenderer, devices, job.test);
    const auto renderer = makeRenderer(testRenderer, devices, job.test);
    Measured m;
    m.sequence.emplace();
    m.sequence->fps = job.test.scene.sequence->fps;
    std::map<std::string, std::vector<double>> times;
    double worst = -INFINITY;  // as report::worstFrame picks the shown frame
    m.sequence->frames = compareSequenceFrames(
        job.test, convergence ? *job.tight : job.test,
        convergence ? job.tightOverrides : job.testOverrides, *renderer, testRenderer, cache, o.ppd,
        o.flipOver, [&](const SequenceStep& step) {
            for (const auto& [stage, ms] : step.test.timingsMs)
                if (stage != "compile") times[stage].push_back(ms);
            const double flip = step.result.values.at("beauty.flip");
            if (step.index > 0 && !(flip > worst)) return;
            if (flip > worst) worst = flip;
            m.shown = step.test;
            m.flipMap = {{"beauty.flip", step.result.errorMaps.at("beauty.flip")}};
            row.referenceKey = step.referenceKey;
        });
    m.sequence->shownFrame = report::worstFrame(m.sequence->frames);
    for (const auto& [stage, v] : times) row.timingsMs[stage] = report::median(v);
    m.checked = report::summariseSequence(m.sequence->frames);
    m.checked["time." + testRenderer + "_ms"] = row.timingsMs.at("total");
    // The row's times are its stages (time.* columns), as a still scene's row.
    for (const auto& [key, v] : m.checked)
        if (!key.starts_with("time.")) row.metrics[key] = v;
    addCounters(m.shown, row.metrics);
    addCounters(m.shown, m.checked);
    return m;
}

std::string combinationDir(std::size_t index, std::size_t total) {
    const int digits = std::max<int>(3, static_cast<int>(std::to_string(total - 1).size()));
    return fmt::format("combinations/c{:0{}}", index, digits);
}

}  // namespace

std::pair<std::string, std::vector<std::string>> parseVary(const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0)
        throw core::InputError(fmt::format(
            "--vary {}: expected KEY=V1,V2,... (e.g. realtime.ssss.enabled=true,false)", text));
    std::string key = text.substr(0, eq);
    std::vector<std::string> values;
    std::string cur;
    int depth = 0;
    char quote = 0;
    for (char c : text.substr(eq + 1)) {
        if (quote) {
            if (c == quote) quote = 0;
        } else if (c == '"' || c == '\'') {
            quote = c;
        } else if (c == '[' || c == '{') {
            ++depth;
        } else if (c == ']' || c == '}') {
            --depth;
        } else if (c == ',' && depth == 0) {
            values.push_back(cur);
            cur.clear();
            continue;
        }
        cur += c;
    }
    values.push_back(cur);
    for (const auto& v : values)
        if (v.empty())
            throw core::InputError(
                fmt::format("--vary {}: an empty value; give values separated by commas", text));
    std::set<std::string> unique(values.begin(), values.end());
    if (unique.size() != values.size())
        throw core::InputError(fmt::format("--vary {}: a value is given twice", text));
    return {key, values};
}

std::vector<std::string> combination(
    const std::vector<std::pair<std::string, std::vector<std::string>>>& vary, std::size_t index) {
    std::vector<std::string> out(vary.size());
    for (std::size_t k = vary.size(); k-- > 0;) {
        const auto& values = vary[k].second;
        out[k] = vary[k].first + "=" + values[index % values.size()];
        index /= values.size();
    }
    return out;
}

namespace {

// The sweep's combinations, each loaded and checked, and what they share: everything is read
// and checked before the first render.
struct SweepPlan {
    std::vector<std::pair<std::string, std::vector<std::string>>> vary;
    bool convergence = false;  // raymarch.* keys varied: the raymarcher against a tight render
    std::string testRenderer;  // "realtime", or "raymarch" for convergence
    int frames = 0;            // per combination
    std::optional<Shard> shard;
    std::optional<compare::Thresholds> thresholds;
    std::size_t total = 1;  // combinations
    double tightTolerance = TIGHT_ROOT_TOLERANCE;
    int tightSpp = TIGHT_SPP;
    std::vector<Job> jobs;  // the shard's combinations
    bool sequence = false;  // a sequence scene: each combination renders every frame
    std::size_t count = 0;  // its frames, as the first combination has them
};

SweepPlan planSweep(const SweepOptions& o) {
    SweepPlan plan;
    auto& [vary, convergence, testRenderer, frames, shard, thresholds, total, tightTolerance,
           tightSpp, jobs, sequence, count] = plan;
    for (const auto& v : o.vary) {
        auto parsed = parseVary(v);
        for (const auto& [k, _] : vary)
            if (k == parsed.first)
                throw core::InputError(fmt::format("--vary {}: the key is varied twice", k));
        vary.push_back(std::move(parsed));
    }
    if (vary.empty()) throw core::InputError("sweep: give at least one --vary KEY=V1,V2,...");
    bool anyRealtime = false, anyRaymarch = false;
    for (const auto& [k, _] : vary) {
        anyRealtime = anyRealtime || k.starts_with("realtime.");
        anyRaymarch = anyRaymarch || k.starts_with("raymarch.");
    }
    if (anyRealtime && anyRaymarch)
        throw core::InputError(
            "sweep: vary realtime.* keys (the real-time renderer against the reference) and "
            "raymarch.* keys (the reference's convergence) in separate sweeps");
    convergence = anyRaymarch;
    testRenderer = convergence ? "raymarch" : "realtime";
    if (o.frames < 0 || o.frames > 1000)
        throw core::InputError(fmt::format("--frames {}: give 1..1000", o.frames));
    frames = o.frames > 0 ? o.frames : (convergence ? 1 : 5);
    // The metric must be one the comparison computes (compare/metric_table.h), or on a
    // sequence scene one its summary pools over the frames (checked below).
    const std::vector<std::string> pooled = report::pooledTemporalMetrics();
    const bool pooledMetric = std::find(pooled.begin(), pooled.end(), o.metric) != pooled.end();
    if (!compare::computedByComparison(o.metric) && !pooledMetric)
        throw core::InputError(
            fmt::format("--metric {}: not a metric; metrics are {}, and on a sequence scene {}",
                        o.metric, compare::metricNames(true), fmt::join(pooled, ", ")));
    if (!o.shard.empty()) shard = parseShard(o.shard);
    if (!o.thresholds.empty()) thresholds = compare::Thresholds::parseFile(o.thresholds);
    if (!fs::is_regular_file(o.scene))
        throw core::InputError(
            fmt::format("{}: scene file not found; give the path of a .toml scene", o.scene));

    for (const auto& [k, values] : vary) total *= values.size();
    if (convergence)
        for (const auto& [k, values] : vary)
            for (const auto& v : values) {
                // Tighter than the sweep's tightest: numbers as given (loadScene checks them).
                char* end = nullptr;
                const double x = std::strtod(v.c_str(), &end);
                if (end == v.c_str() || *end) continue;
                if (k == "raymarch.root_tolerance")
                    tightTolerance = std::min(tightTolerance, x / 10.0);
                if (k == "raymarch.spp") tightSpp = std::max(tightSpp, static_cast<int>(x) * 4);
            }
    tightTolerance = std::max(tightTolerance, 1e-8);  // the raymarcher's lower bound
    tightSpp = std::min(tightSpp, 1024);

    for (std::size_t i = 0; i < total; ++i) {
        Job job;
        job.index = i;
        job.varied = combination(vary, i);
        job.testOverrides = o.sets;
        job.testOverrides.insert(job.testOverrides.end(), job.varied.begin(), job.varied.end());
        try {
            job.test = loadScene(o.scene, job.testOverrides);
        } catch (const core::InputError& e) {
            // The scene parser names overrides "--set KEY=VALUE"; say --vary for varied ones.
            std::string message = e.what(), which;
            for (const auto& v : job.varied) {
                which += (which.empty() ? "" : ", ") + v;
                if (message.rfind("--set " + v + ":", 0) == 0) message.replace(0, 5, "--vary");
            }
            throw core::InputError(fmt::format("{} (in the combination {})", message, which));
        }
        if (i == 0) {
            sequence = job.test.scene.sequence.has_value();
            if (sequence) count = core::sequenceFrames(job.test.scene).size();
        }
        if (job.test.scene.sequence.has_value() != sequence)
            throw core::InputError(fmt::format(
                "sweep: the combination {} makes {} {}a sequence scene and the first does not; "
                "sweep a sequence scene and a still one separately",
                fmt::join(job.varied, ", "), o.scene, sequence ? "not " : ""));
        // The report's frame count (its charts' axis, the merge of its shards) holds for every
        // combination: varied sequence.* keys must keep the number of frames.
        if (sequence && core::sequenceFrames(job.test.scene).size() != count)
            throw core::InputError(fmt::format(
                "sweep: the combination {} gives {} frames and the first {}; vary the "
                "sequence's frames in separate sweeps",
                fmt::join(job.varied, ", "), core::sequenceFrames(job.test.scene).size(), count));
        // The bounds as `run` takes them: the file's, the scene file's own, the file's
        // [scenes.NAME].
        if (thresholds)
            job.bounds = thresholds->forScene(job.test.scene.name, &job.test.scene.compare);
        if (convergence) {
            for (const auto& s : job.testOverrides)
                if (!(s.starts_with("raymarch.") &&
                      std::any_of(vary.begin(), vary.end(),
                                  [&](const auto& kv) { return kv.first == keyOf(s); })) &&
                    keyOf(s) != "raymarch.root_tolerance" && keyOf(s) != "raymarch.spp")
                    job.tightOverrides.push_back(s);
            job.tightOverrides.push_back(fmt::format("raymarch.root_tolerance={}", tightTolerance));
            job.tightOverrides.push_back(fmt::format("raymarch.spp={}", tightSpp));
        }
        // Only this shard's combinations are kept; every one is checked, so all shards fail alike.
        if (shard && !shard->takes(i)) continue;
        if (convergence) job.tight = loadScene(o.scene, job.tightOverrides);
        jobs.push_back(std::move(job));
    }

    if (pooledMetric && !sequence)
        throw core::InputError(fmt::format(
            "--metric {}: a sequence's metric, pooled over its frames, and {} renders one frame; "
            "give a scene with a [sequence] table or a sequence body (docs/scenes.md, "
            "\"Sequences\"), or "
            "one of {}",
            o.metric, o.scene, compare::metricNames(true)));
    return plan;
}

// The references of the plan's combinations, as forEachSweepReference gives them.
void visitReferences(SweepPlan& plan, const ReferenceVisit& visit) {
    for (Job& job : plan.jobs) {
        LoadedScene& reference = plan.convergence ? *job.tight : job.test;
        const std::vector<std::string>& overrides =
            plan.convergence ? job.tightOverrides : job.testOverrides;
        if (!plan.sequence) {
            visit(reference, overrides, std::nullopt);
            continue;
        }
        for (const std::int64_t n : core::sequenceFrames(job.test.scene)) {
            setFrame(reference, n);
            visit(reference, overrides, n);
        }
    }
}

}  // namespace

void forEachSweepReference(const SweepOptions& o, const ReferenceVisit& visit) {
    SweepPlan plan = planSweep(o);
    visitReferences(plan, visit);
}

ExitCode runSweep(const SweepOptions& o) {
    const bool tty = isatty(STDERR_FILENO);
    if (!o.tiles.empty())
        refuseTilesWith("sweep", "the combinations", !o.shard.empty(), !o.cache.empty());
    SweepPlan plan = planSweep(o);
    auto& [vary, convergence, testRenderer, frames, shard, thresholds, total, tightTolerance,
           tightSpp, jobs, sequence, count] = plan;
    // Tiles of the references: the merge renders and compares the rest.
    if (!o.tiles.empty())
        return sweepTiles([&](const ReferenceVisit& visit) { visitReferences(plan, visit); },
                          parseTiles(o.tiles), o);
    if (sequence) {
        // Each frame of a sequence is a new particle set, rendered once: its cost is that
        // first render, which timing repeated renders of one set would hide.
        if (o.frames > 0)
            std::printf(
                "note: --frames %d is not used on a sequence scene: each of its %zu frames is a "
                "new particle set, rendered once, and a combination's time is the median "
                "frame's\n",
                o.frames, count);
        frames = static_cast<int>(count);
    }

    const fs::path out(o.out);
    const fs::path cacheDir = o.cache.empty() ? out / "reference_cache" : fs::path(o.cache);
    Devices devices(o.requireGpu, {.force = o.selfCheck, .cache = o.cache});
    if (!convergence) devices.realtime();  // no GL context: fail before the first render
    prepareOutputFolder(out);
    prepareOutputFolder(cacheDir);
    ReferenceCache cache(cacheDir, devices);

    report::SweepReport report;
    report.scene =
        jobs.empty() ? loadScene(o.scene, o.sets).scene.name : jobs.front().test.scene.name;
    report.sceneFile = o.scene;
    report.mode = testRenderer;
    report.testRenderer = testRenderer;
    report.referenceDescription =
        convergence
            ? fmt::format("raymarch, root_tolerance {:g} h, spp {}", tightTolerance, tightSpp)
            : "raymarch (the scene's settings)";
    for (const auto& [k, _] : vary) report.keys.push_back(k);
    report.metric = o.metric;
    report.frames = frames;
    report.sequence = sequence;
    report.combinations = total;
    report.createdAt = nowUtc();
    report.commandLine = o.commandLine;
    report.thresholdsFile = o.thresholds;

    for (std::size_t j = 0; j < jobs.size(); ++j) {
        Job& job = jobs[j];
        report::SweepRow row;
        row.index = job.index;
        for (std::size_t k = 0; k < vary.size(); ++k)
            row.settings.emplace_back(vary[k].first,
                                      job.varied[k].substr(vary[k].first.size() + 1));
        row.dir = combinationDir(job.index, total);
        if (tty) std::fprintf(stderr, "[%zu/%zu] %s\n", j + 1, jobs.size(), row.label().c_str());
        try {
            Measured measured =
                sequence ? measureSequence(job, row, testRenderer, o, devices, cache)
                         : measureStill(job, row, testRenderer, frames, o, devices, cache);
            const core::Frame& test = measured.shown;

            // The combination's folder: its render, the ꟻLIP map, its metrics.
            const fs::path dir = out / row.dir;
            core::makeFolders(dir);
            core::writeImage(test.display, dir / (testRenderer + ".png"));
            report::SceneReport scene;
            scene.name = job.test.scene.name;
            scene.description = row.label();
            scene.metrics = row.metrics;
            report::RendererReport rr;
            rr.timingsMs = row.timingsMs;
            rr.device = test.device;
            rr.counters = test.counters;
            rr.images["beauty"] = testRenderer + ".png";
            scene.renderers[testRenderer] = rr;
            scene.errorMaps = compare::writeErrorMapImages(measured.flipMap, dir);
            if (thresholds) {
                scene.checks = compare::evaluate(measured.checked, job.bounds);
                report::recordChecks(row, scene.checks);
            }
            json settings = json::object();
            for (const auto& [k, v] : row.settings) settings[k] = v;
            scene.settings = {{"varied", settings},
                              {"scene_file", job.test.scene.file.string()},
                              {testRenderer, test.settings},
                              {"reference_key", row.referenceKey}};
            if (measured.sequence) {
                scene.settings["sequence"] =
                    sequenceSettings(*job.test.scene.sequence, measured.sequence->frames.size());
                scene.sequence = std::move(measured.sequence);
            }
            report::writeMetricsJson(scene, dir / "metrics.json");
            const auto m = row.metrics.find(o.metric);
            std::printf("[%zu/%zu] %s: %s %.2f ms, %s %s%s\n", j + 1, jobs.size(),
                        row.label().c_str(), testRenderer.c_str(), row.timingsMs.at("total"),
                        o.metric.c_str(),
                        m == row.metrics.end() ? "-" : compare::formatValue(m->second).c_str(),
                        verdictSuffix(row).c_str());
        } catch (const core::InputError&) {
            throw;
        } catch (const std::exception& e) {
            // One combination that cannot be rendered fails; the others still run.
            row.error = e.what();
            if (thresholds) report::recordChecks(row, {});
            std::printf("[%zu/%zu] %s: error: %s\n", j + 1, jobs.size(), row.label().c_str(),
                        e.what());
        }
        std::fflush(stdout);
        report.rows.push_back(std::move(row));
    }
    // A signal during the renders leaves no report; one from here on lets it finish.
    throwIfInterrupted();
    json manifest;
    if (shard) {
        json indices = json::array();
        for (const auto& r : report.rows) indices.push_back(r.index);
        json settings = {{"scene", fs::absolute(o.scene).lexically_normal().string()},
                         {"vary", o.vary},
                         {"sets", o.sets},
                         {"metric", o.metric},
                         {"thresholds", o.thresholds},
                         {"frames", frames},
                         {"ppd", o.ppd},
                         {"flip_over", o.flipOver}};
        manifest = {{"command", "sweep"},          {"settings", settings},
                    {"combinations", total},       {"indices", indices},
                    {"created", report.createdAt}, {"command_line", o.commandLine}};
    }
    // A structured binding reaches a lambda through a capture of its own: clang before 16
    // does not capture one implicitly.
    writeTogether(out, [&, &shard = shard](const fs::path& staging) {
        report::writeSweepReport(report, staging);
        if (shard) writeShardManifest(*shard, manifest, staging);
    });
    std::printf("%zu combinations -> %s, %s\n", report.rows.size(), (out / "sweep.csv").c_str(),
                (out / "index.html").c_str());
    if (!shard) return finishSweep(report);
    // A shard holds part of the combinations: whether one passes is for the merged sweep to
    // say, so a shard fails only when a combination could not be rendered.
    for (const auto& line : report::verdictLines(report))
        std::printf("shard %d/%d: %s\n", shard->index, shard->count, line.c_str());
    return anyRowError(report) ? ExitCode::Fail : ExitCode::Pass;
}

ExitCode finishSweep(const report::SweepReport& report) {
    for (const auto& line : report::verdictLines(report)) std::printf("%s\n", line.c_str());
    if (!report.thresholdsFile.empty()) return exitCodeOf(report::sweepStatus(report));
    return anyRowError(report) ? ExitCode::Fail : ExitCode::Pass;
}

}  // namespace twinrender::app
