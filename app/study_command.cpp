#include "app/study_command.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "app/comparison.h"
#include "app/interruption.h"
#include "app/output_folder.h"
#include "app/reference_cache.h"
#include "app/studies.h"
#include "compare/contact_band.h"
#include "compare/flip.h"
#include "compare/masks.h"
#include "compare/metrics.h"
#include "compare/temporal_error.h"
#include "compare/thresholds.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/install_layout.h"

namespace twinrender::app {

namespace fs = std::filesystem;

namespace {

// Radius of the contact band, pixels: the blur's reach at the study's sizes plus the pixel
// the footprint mixes.
constexpr int CONTACT_BAND_PX = 3;

// What is left of a run of studies, said on the line each point prints: the points done of
// all the studies' points, and the time left at the pace so far.
class Remaining {
  public:
    explicit Remaining(std::size_t total) : mTotal(total) {}
    std::string pointDone() {
        ++mDone;
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - mStart).count();
        const double left = elapsed / static_cast<double>(mDone) *
                            static_cast<double>(mTotal - std::min(mDone, mTotal));
        return fmt::format("{}/{} points, about {:.0f} s left", mDone, mTotal, left);
    }

  private:
    std::size_t mTotal, mDone = 0;
    std::chrono::steady_clock::time_point mStart = std::chrono::steady_clock::now();
};

fs::path defaultStudyScenes() {
    if (fs::is_directory("scenes/studies")) return "scenes/studies";
    return core::resourceDir() / "scenes" / "studies";
}

struct Point {
    StudyPoint point;
    fs::path file;  // the scene file
    std::vector<std::string> overrides;
    // Loaded once to check it before the first render, then held without its particles and
    // textures (a full methods study's 432 points held 3 GB with them) until its renders:
    // `loaded` says whether they are there.
    LoadedScene scene;
    bool loaded = false;
};

struct Planned {
    const StudyDef* def;
    std::vector<fs::path> sceneFiles;  // every scene its points render, in order of first use
    std::vector<Point> points;
};

// Loads the scene of every point in [first, end) that is not loaded (the same scene as the
// check before the first render loaded: files, overrides and loadScene are deterministic).
void loadPoints(Planned& plan, std::size_t first, std::size_t end) {
    for (std::size_t k = first; k < end; ++k) {
        Point& pt = plan.points[k];
        if (pt.loaded) continue;
        pt.scene = loadScene(pt.file, pt.overrides);
        pt.loaded = true;
    }
}

// Drops what a point's scene holds for its renders, once they are done.
void unloadPoint(Point& pt) {
    pt.scene.particles = core::SceneParticles{};
    pt.scene.materials = {};
    pt.loaded = false;
}

// The end of the run of points from `first` whose frames are timed together: for a study that
// compares costs, the consecutive points of one scene file (their frames in rounds: see
// renderTimedRounds); else the point alone.
std::size_t timedTogetherEnd(const Planned& plan, std::size_t first) {
    std::size_t end = first + 1;
    if (plan.def->frames > 1)
        while (end < plan.points.size() &&
               plan.points[end].point.scene == plan.points[first].point.scene)
            ++end;
    return end;
}

// Renders the real-time frames of the points [first, end) (timedTogetherEnd) and their median
// stage times: one frame each for a stability study; for a study that compares costs, one
// untimed warm-up frame each and then `frames` rounds (one in quick runs).
// The last frame of each gets its reference's AOV image for the error split (the references
// are rendered or read first).
void renderPoints(const Planned& plan, std::size_t first, std::size_t end, bool quick,
                  Devices& devices, ReferenceCache& cache,
                  std::vector<std::optional<TimedFrame>>& timed) {
    const StudyDef& d = *plan.def;
    std::vector<const LoadedScene*> scenes;
    std::vector<const core::Image*> references;
    for (std::size_t k = first; k < end; ++k) {
        const Point& pt = plan.points[k];
        scenes.push_back(&pt.scene);
        const auto [key, what] = referenceKey(pt.scene, pt.overrides);
        references.push_back(&cache.get(pt.scene, key, what).image);
    }
    const int frames = quick ? 1 : std::max(d.frames, 1);
    if (scenes.size() > 1) {
        std::printf("[%s] %s: %zu settings, %d frame%s each in rounds after a warm-up frame\n",
                    d.name.c_str(), plan.points[first].scene.scene.name.c_str(), scenes.size(),
                    frames, frames == 1 ? "" : "s");
        std::fflush(stdout);
    }
    auto frameTimes =
        renderTimedRounds("realtime", devices, scenes, frames, d.frames > 1, references);
    for (std::size_t k = first; k < end; ++k) timed[k] = std::move(frameTimes[k - first]);
}

}  // namespace

ExitCode runStudies(const StudyOptions& o) {
    // ---- Everything is read and checked before the first render. ----
    std::vector<const StudyDef*> chosen;
    if (o.names.empty())
        for (const StudyDef& d : studies()) chosen.push_back(&d);
    std::set<std::string> seen;
    for (const std::string& n : o.names) {
        const StudyDef* found = findStudy(n);
        if (!found)
            throw core::InputError(
                fmt::format("study {}: no such study; the studies are {}", n, studyNames()));
        if (!seen.insert(n).second) throw core::InputError(fmt::format("study {}: named twice", n));
        chosen.push_back(found);
    }
    const fs::path scenesDir = o.scenesDir.empty() ? defaultStudyScenes() : fs::path(o.scenesDir);
    std::vector<Planned> plans;
    for (const StudyDef* d : chosen) {
        Planned p{d, {}, {}};
        for (StudyPoint& sp : d->points(o.quick)) {
            const fs::path sceneFile =
                (scenesDir / (sp.scene.empty() ? d->scene : sp.scene)).lexically_normal();
            if (std::find(p.sceneFiles.begin(), p.sceneFiles.end(), sceneFile) ==
                p.sceneFiles.end()) {
                if (!fs::is_regular_file(sceneFile))
                    throw core::InputError(fmt::format("{}: the scene of study {} is missing",
                                                       sceneFile.string(), d->name));
                p.sceneFiles.push_back(sceneFile);
            }
            Point pt;
            pt.overrides = o.sets;
            pt.overrides.insert(pt.overrides.end(), sp.sets.begin(), sp.sets.end());
            try {
                pt.scene = loadScene(sceneFile, pt.overrides);
            } catch (const core::InputError& e) {
                throw core::InputError(
                    fmt::format("study {}, {}{} at x = {}: {}", d->name,
                                sp.scene.empty() ? "" : sceneFile.stem().string() + ", ", sp.series,
                                sp.x, e.what()));
            }
            if (std::isnan(sp.x) && d->xOf) sp.x = d->xOf(pt.scene);
            pt.file = sceneFile;
            unloadPoint(pt);  // loaded again for its renders
            pt.point = std::move(sp);
            p.points.push_back(std::move(pt));
        }
        plans.push_back(std::move(p));
    }

    std::optional<compare::Bounds> suiteBounds;
    if (const fs::path t = (scenesDir / ".." / "thresholds.toml").lexically_normal();
        fs::is_regular_file(t))
        suiteBounds = compare::Thresholds::parseFile(t).global();

    const fs::path out(o.out);
    const fs::path cacheDir = o.cache.empty() ? out / "reference_cache" : fs::path(o.cache);
    Devices devices(o.requireGpu, {.force = o.selfCheck, .cache = o.cache});
    devices.realtime();  // no GL context: fail before the first render
    prepareOutputFolder(out);
    prepareOutputFolder(cacheDir);
    ReferenceCache cache(cacheDir, devices);

    std::vector<report::StudyResult> results;
    bool anyError = false;
    std::size_t totalPoints = 0;
    for (const Planned& plan : plans) totalPoints += plan.points.size();
    Remaining remaining(totalPoints);
    for (Planned& plan : plans) {
        const StudyDef& d = *plan.def;
        const auto start = std::chrono::steady_clock::now();
        report::StudyResult s;
        s.name = d.name;
        s.title = d.title;
        s.question = d.question;
        for (const fs::path& f : plan.sceneFiles)
            s.sceneFile += (s.sceneFile.empty() ? "" : ", ") + f.string();
        s.xLabel = d.xLabel;
        s.xLog = d.xLog;
        s.metric = d.metric;
        s.columns = d.columns;
        // The study's images, by path under OUT/NAME: written with its report, so that a
        // signal or an error during the renders leaves nothing of it.
        std::map<std::string, core::Image> images;
        std::map<std::string, double> unbracketed;  // per distinct reference
        // Frame-to-frame: the previous frame's renders (reference, real-time), per series.
        std::map<std::string, std::pair<core::Frame, core::Frame>> previous;
        std::vector<std::optional<TimedFrame>> timed(plan.points.size());
        for (std::size_t i = 0; i < plan.points.size(); ++i) {
            // The point's scene, and those of the points whose frames are timed with it.
            if (!plan.points[i].loaded) loadPoints(plan, i, timedTogetherEnd(plan, i));
            const Point& pt = plan.points[i];
            report::StudyRow row;
            if (!pt.point.scene.empty()) row.scene = pt.scene.scene.name;
            row.series = pt.point.series;
            row.x = pt.point.x;
            row.sets = pt.point.sets;
            try {
                const auto [key, what] = referenceKey(pt.scene, pt.overrides);
                row.referenceKey = key;
                const core::Frame& ref = cache.get(pt.scene, key, what);
                row.referenceMs = ref.timingsMs.count("total") ? ref.timingsMs.at("total") : NAN;
                const auto u = ref.counters.find("unbracketed_rays");
                row.metrics["count.unbracketed_rays"] = u == ref.counters.end() ? 0.0 : u->second;
                unbracketed[key] = row.metrics["count.unbracketed_rays"];
                // The reference's stated noise where it samples occlusion or emitted light: what
                // a study's ties on those metrics rest on.
                for (const char* counter : {"ao_standard_error", "irradiance_standard_error"})
                    if (const auto c = ref.counters.find(counter); c != ref.counters.end())
                        row.metrics[std::string("reference.") + counter] = c->second;
                if (!timed[i])
                    renderPoints(plan, i, timedTogetherEnd(plan, i), o.quick, devices, cache,
                                 timed);
                const core::Frame test = std::move(timed[i]->frame);
                row.timingsMs = std::move(timed[i]->fastestMs);
                timed[i].reset();
                const compare::MetricSettings ms = metricSettings(pt.scene, o.ppd);
                compare::MetricResult m = compare::computeMetrics(ref.image, test.image, ms);
                addSplitMetrics(ref, test, ms, m.values);
                for (const auto& [k, v] : m.values) row.metrics[k] = v;
                if (d.contactBand || d.occlusionError) {
                    const compare::Masks masks =
                        compare::computeMasks(ref.image, test.image, compare::maskSettings(ms));
                    if (d.occlusionError) {
                        const double covered = double(masks.referenceCovered.count());
                        row.metrics["occlusion.error"] =
                            covered > 0 ? 1.0 - double(masks.sameBody.count()) / covered : NAN;
                    }
                    if (d.contactBand) {
                        const auto band = compare::contactBandError(ref.image, test.image, masks,
                                                                    CONTACT_BAND_PX);
                        row.metrics["contact.uv_mean"] = band.uvMean;
                        row.metrics["contact.emission_rmse"] = band.emissionRmse;
                        row.metrics["contact.pixels"] = double(band.pixels);
                    }
                }
                if (d.frameToFrame) {
                    const auto prev = previous.find(row.series);
                    compare::FlipSettings fs;
                    fs.ppd = o.ppd;
                    if (prev != previous.end()) {
                        const auto& [prevRef, prevTest] = prev->second;
                        compare::addFrameChangeMetrics(
                            compare::frameChange(
                                {prevRef.image, prevRef.display}, {ref.image, ref.display},
                                {prevTest.image, prevTest.display}, {test.image, test.display}, fs),
                            row.metrics);
                    }
                    previous[row.series] = {ref, test};
                }
                const std::string png = fmt::format("points/{:03}.realtime.png", i);
                images[png] = test.display;
                row.images["realtime"] = png;
                const std::string refPng = "references/" + key + ".png";
                images.try_emplace(refPng, ref.display);
                row.images["reference"] = refPng;
                const auto y = row.metrics.find(d.metric);
                std::printf(
                    "[%s %zu/%zu; %s] %s%s%s, x = %g: %s %s (real-time %.1f ms)\n", d.name.c_str(),
                    i + 1, plan.points.size(), remaining.pointDone().c_str(), row.scene.c_str(),
                    row.scene.empty() ? "" : ": ", row.series.c_str(), row.x, d.metric.c_str(),
                    y == row.metrics.end() ? "-" : compare::formatValue(y->second).c_str(),
                    row.timingsMs.count("total") ? row.timingsMs.at("total") : NAN);
            } catch (const core::InputError&) {
                throw;
            } catch (const std::exception& e) {
                // One point that cannot be rendered fails; the others still run.
                row.error = e.what();
                anyError = true;
                std::printf("[%s %zu/%zu; %s] %s%s%s, x = %g: error: %s\n", d.name.c_str(), i + 1,
                            plan.points.size(), remaining.pointDone().c_str(), row.scene.c_str(),
                            row.scene.empty() ? "" : ": ", row.series.c_str(), row.x, e.what());
            }
            std::fflush(stdout);
            s.rows.push_back(std::move(row));
            unloadPoint(plan.points[i]);
        }
        s.references = unbracketed.size();
        for (const auto& [k, n] : unbracketed) s.unbracketedRays += n;
        d.conclude(s);
        // The suite's bound of the charted metric, where it has one (scenes/thresholds.toml,
        // beside the studies' folder): a reader sees where a setting leaves the default bounds.
        if (!s.scatter && s.chart.yMarks.empty() && suiteBounds)
            s.chart.yMarks = report::boundMarks(*suiteBounds, d.metric);
        s.wallSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        // A signal during the renders leaves no report of this study; one from here on lets
        // it finish.
        throwIfInterrupted();
        writeTogether(out, [&](const fs::path& staging) {
            for (const auto& [path, image] : images)
                core::writeImage(image, staging / d.name / path);
            report::writeStudy(s, staging);
        });
        std::printf("%s: %s [reference: %s unbracketed rays in %zu renders; %.1f s]\n",
                    d.name.c_str(), s.finding.c_str(),
                    compare::formatValue(s.unbracketedRays).c_str(), s.references, s.wallSeconds);
        std::fflush(stdout);
        results.push_back(std::move(s));
    }
    writeTogether(out, [&](const fs::path& staging) {
        report::writeStudiesIndex(results, staging, nowUtc(), o.commandLine, o.quick, o.back);
    });
    std::printf("%zu stud%s -> %s\n", results.size(), results.size() == 1 ? "y" : "ies",
                (out / "index.html").c_str());
    return anyError ? ExitCode::Fail : ExitCode::Pass;
}

}  // namespace twinrender::app
