#include "app/sequence_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>

#include "app/comparison.h"
#include "app/video_encoder.h"
#include "compare/flip.h"
#include "compare/metrics.h"
#include "compare/temporal_error.h"
#include "core/error.h"
#include "core/sequence.h"
#include "report/sequence_report.h"
#include "report/sequence_summary.h"
#include "report/sequence_video.h"

namespace twinrender::app {

namespace fs = std::filesystem;

namespace {

std::optional<std::int64_t> integer(const std::string& text) {
    std::int64_t v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
    return v;
}

// A frame's images prefixed with its folder, so that the scene page (one folder up) finds them.
void prefixImages(report::SceneReport& report, const std::string& prefix) {
    for (auto& [name, r] : report.renderers)
        for (auto& [buffer, path] : r.images) path = prefix + path;
    for (auto& [buffer, m] : report.errorMaps) m.path = prefix + m.path;
}

}  // namespace

std::vector<std::string> framesOverrides(const std::string& frames) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (;;) {
        const auto colon = frames.find(':', start);
        parts.push_back(frames.substr(start, colon - start));
        if (colon == std::string::npos) break;
        start = colon + 1;
    }
    std::vector<std::int64_t> v;
    for (const std::string& p : parts)
        if (auto n = integer(p)) v.push_back(*n);
    if (v.size() != parts.size() || v.empty() || v.size() > 3 || (v.size() == 3 && v[2] < 1) ||
        (v.size() >= 2 && v[1] < v[0]))
        throw core::InputError(fmt::format(
            "--frames {}: expected FIRST:LAST (or FIRST:LAST:STEP, or one FRAME) with integer "
            "frame numbers, FIRST <= LAST and STEP >= 1, e.g. --frames 0:40",
            frames));
    std::vector<std::string> sets = {fmt::format("sequence.first={}", v[0]),
                                     fmt::format("sequence.last={}", v.size() > 1 ? v[1] : v[0])};
    if (v.size() == 3) sets.push_back(fmt::format("sequence.step={}", v[2]));
    return sets;
}

std::string frameFolder(std::int64_t frame) {
    return frame < 0 ? fmt::format("-{:04d}", -frame) : fmt::format("{:04d}", frame);
}

void setFrame(LoadedScene& s, std::int64_t frame) {
    if (s.scene.frame == frame && !s.particles.particles.position.empty()) return;
    s.scene = core::frameScene(s.scene, frame);
    s.particles = core::buildParticles(s.scene);
}

void renderFrames(LoadedScene& s, const std::vector<std::string>& names, Devices& devices,
                  const fs::path& dir) {
    std::vector<std::unique_ptr<core::Renderer>> renderers;
    for (const auto& name : names) renderers.push_back(makeRenderer(name, devices, s));
    for (std::int64_t n : core::sequenceFrames(s.scene)) {
        setFrame(s, n);
        const fs::path frameDir = dir / frameFolder(n);
        for (std::size_t i = 0; i < names.size(); ++i) {
            const core::Frame frame = render(*renderers[i], names[i], s);
            writeRender(s, frame, frameDir);
            std::printf("%s: frame %lld: %s %dx%d, %zu particles, %.1f ms -> %s\n",
                        s.scene.name.c_str(), static_cast<long long>(n), frame.renderer.c_str(),
                        frame.image.width(), frame.image.height(), frame.particleCount,
                        frame.timingsMs.at("total"),
                        (frameDir / (frame.renderer + ".exr")).c_str());
            std::fflush(stdout);
        }
    }
}

nlohmann::json sequenceSettings(const core::SequenceSettings& q, std::size_t frames) {
    const char* camera = q.camera == core::CameraPath::Orbit  ? "orbit"
                         : q.camera == core::CameraPath::Keys ? "keys"
                                                              : "fixed";
    return {{"first", q.first}, {"last", q.last},   {"step", q.step},
            {"fps", q.fps},     {"camera", camera}, {"frames", frames}};
}

std::vector<report::SequenceFrame> compareSequenceFrames(
    LoadedScene& s, LoadedScene& referenceScene, const std::vector<std::string>& referenceOverrides,
    core::Renderer& renderer, std::string_view rendererName, ReferenceCache& cache, double ppd,
    double flipOver, const std::function<void(const SequenceStep&)>& visit) {
    const std::vector<std::int64_t> frames = core::sequenceFrames(s.scene);
    std::vector<report::SequenceFrame> out;
    std::optional<std::pair<core::Frame, core::Frame>> previous;  // reference, real-time
    compare::FlipSettings flip;
    flip.ppd = ppd;
    for (std::size_t k = 0; k < frames.size(); ++k) {
        SequenceStep step;
        step.frame = frames[k];
        step.index = k;
        step.count = frames.size();
        setFrame(s, step.frame);
        if (&referenceScene != &s) setFrame(referenceScene, step.frame);
        const auto [key, what] = referenceKey(referenceScene, referenceOverrides);
        step.referenceKey = key;
        step.reference = cache.get(referenceScene, key, what);
        cache.forget(key);
        step.test = render(renderer, rendererName, s);
        step.result = compare::computeMetrics(step.reference.image, step.test.image,
                                              metricSettings(s, ppd, flipOver));
        step.metrics = step.result.values;
        addTimeMetrics(step.reference, step.test, step.metrics);
        if (previous) {
            const core::Frame &ref = step.reference, &test = step.test;
            step.change = compare::frameChange({previous->first.image, previous->first.display},
                                               {ref.image, ref.display},
                                               {previous->second.image, previous->second.display},
                                               {test.image, test.display}, flip);
            compare::addFrameChangeMetrics(*step.change, step.metrics);
        }
        visit(step);
        out.push_back({.frame = step.frame,
                       .metrics = step.metrics,
                       .notApplicable = step.result.notApplicable});
        previous.emplace(std::move(step.reference), std::move(step.test));
    }
    return out;
}

report::SceneReport runSequence(LoadedScene& s, Devices& devices, ReferenceCache& cache,
                                const SequenceRun& run, const fs::path& dir) {
    const double fps = s.scene.sequence->fps;
    auto tested = makeRenderer(run.test, devices, s);
    VideoEncoder video(dir / "sequence.mp4", dir / "sequence.webm", fps);
    report::SequenceReport sequence;
    sequence.fps = fps;
    std::vector<report::SceneReport> frameReports;
    sequence.frames = compareSequenceFrames(
        s, s, run.overrides, *tested, run.test, cache, run.ppd, run.flipOver,
        [&](const SequenceStep& step) {
            const std::string folder = "frames/" + frameFolder(step.frame) + "/";
            writeRender(s, step.reference, dir / folder);
            writeRender(s, step.test, dir / folder);
            report::SceneReport report = sceneReport(s, step.reference, step.test, step.result,
                                                     run.bounds, nullptr, dir / folder);
            report.metrics = step.metrics;
            const std::string flicker =
                step.change ? fmt::format("{:+.4f}", step.change->flicker()) : "-";
            const double flipMean = step.result.values.at("beauty.flip");
            video.add(report::sideBySideFrame(
                step.test.display, step.reference.display, step.result.errorMaps.at("beauty.flip"),
                fmt::format("FRAME {}  FLIP {:.4f}  FLICKER {}", step.frame, flipMean, flicker)));
            const auto testTotal = step.test.timingsMs.find("total");
            const std::string testTime = testTotal == step.test.timingsMs.end()
                                             ? "no time"
                                             : fmt::format("{:.1f} ms", testTotal->second);
            std::printf(
                "%s: frame %lld (%zu/%zu): %s %s, reference %.1f ms, ꟻLIP %.4f, "
                "flicker %s\n",
                s.scene.name.c_str(), static_cast<long long>(step.frame), step.index + 1,
                step.count, run.test == "realtime" ? "real-time" : run.test.c_str(),
                testTime.c_str(), step.reference.timingsMs.at("total"), flipMean, flicker.c_str());
            std::fflush(stdout);
            prefixImages(report, folder);
            frameReports.push_back(std::move(report));
        });
    video.finish();
    sequence.videos = {{"video/webm", "sequence.webm"}, {"video/mp4", "sequence.mp4"}};
    sequence.charts = report::writeSequenceCharts(sequence, dir, run.bounds);
    sequence.shownFrame = report::worstFrame(sequence.frames);
    std::size_t shown = 0;
    while (sequence.frames.at(shown).frame != sequence.shownFrame) ++shown;
    report::SceneReport report = std::move(frameReports.at(shown));
    report.metrics = report::summariseSequence(sequence.frames);
    report.notApplicable = report::notApplicableInEvery(sequence.frames);
    report.settings["sequence"] = sequenceSettings(*s.scene.sequence, sequence.frames.size());
    checkReport(report, run.bounds, run.baseline);
    report.sequence = std::move(sequence);
    return report;
}

}  // namespace twinrender::app
