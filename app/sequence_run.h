// Sequences in the commands that render (docs/cli.md; docs/design.md, "Sequences"): `render SCENE
// --frames A:B` writes each frame's renders into a numbered folder, and `run` renders every frame
// of a sequence scene with both renderers (the reference through the cache of
// app/reference_cache.h, keyed by the frame), compares each pair, measures the temporal error of
// each consecutive pair against the truth (compare/temporal_error.h), and writes the charts, the
// side-by-side video (app/video_encoder.h) and the scene's report, whose metrics summarise the
// frames (report/sequence_summary.h). Every frame is a new particle set for the real-time
// renderer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/reference_cache.h"
#include "app/render_job.h"
#include "compare/baseline.h"
#include "compare/metrics.h"
#include "compare/temporal_error.h"
#include "compare/thresholds.h"
#include "report/report.h"

namespace twinrender::app {

// The overrides of `--frames A:B` (or A:B:STEP, or one frame A): sequence.first, sequence.last
// and sequence.step. Throws core::InputError for anything else.
std::vector<std::string> framesOverrides(const std::string& frames);

// The folder name of a frame, zero-padded to four digits ("0007"; "-0003" below zero).
std::string frameFolder(std::int64_t frame);

// Moves a loaded scene to a frame of its sequence (camera, files, moving bodies) and builds its
// particles anew.
void setFrame(LoadedScene& scene, std::int64_t frame);

// `render --frames`: every frame of the scene's range with each renderer, into
// DIR/<frameFolder>/<renderer>.exr|png|json. Prints a line per render.
void renderFrames(LoadedScene& scene, const std::vector<std::string>& renderers, Devices& devices,
                  const std::filesystem::path& dir);

// One frame of a sequence, rendered by both sides and compared (compareSequenceFrames).
struct SequenceStep {
    std::int64_t frame = 0;
    std::size_t index = 0, count = 0;  // the index-th (from 0) of the range's count frames
    core::Frame reference, test;
    std::string referenceKey;      // the reference's cache key
    compare::MetricResult result;  // compare::computeMetrics of the pair
    // The frame's metrics: result.values, the times (time.<renderer>_ms) and, from the second
    // frame on, the change from the previous frame (temporal.*); what SequenceFrame holds.
    compare::MetricValues metrics;
    std::optional<compare::FrameChange> change;  // none for the first frame
};

// The frames of a sequence compared one by one, as `run` and `sweep` take them: per frame of
// the test scene's range, both scenes moved to it (setFrame; `reference` is the scene of the
// reference's settings, the test scene itself unless a convergence sweep's tight one), the
// reference from the cache (keyed by the frame and `referenceOverrides`, let go of after the
// frame), the test render by `renderer` (`rendererName`; the real-time renderer gets each frame as
// a new particle set: its per-set work is part of the frame's time), the metrics (with `ppd` and
// `flipOver`) and the change from the previous frame (compare/temporal_error.h). `visit` sees
// each step before the next frame renders. Returns the frames' metrics, for
// report::summariseSequence.
std::vector<report::SequenceFrame> compareSequenceFrames(
    LoadedScene& test, LoadedScene& reference, const std::vector<std::string>& referenceOverrides,
    core::Renderer& renderer, std::string_view rendererName, ReferenceCache& cache, double ppd,
    double flipOver, const std::function<void(const SequenceStep&)>& visit);

// A sequence's settings as a report's settings show them: first, last, step, fps, camera and
// the count of frames in the range.
nlohmann::json sequenceSettings(const core::SequenceSettings& sequence, std::size_t frames);

struct SequenceRun {
    std::vector<std::string> overrides;  // the run's --set, for the reference cache's keys
    compare::Bounds bounds;
    const compare::Baseline* baseline = nullptr;
    double ppd = 67.0;
    double flipOver = 0.5;
    // The renderer measured, as makeRenderer names it: "realtime", "external" (a command of
    // one's own, a request per frame) or "images" (images rendered earlier, one per frame).
    std::string test = "realtime";
};

// `run` on a sequence scene: see above, with `run.test` as the test renderer. Writes
// DIR/frames/<frameFolder>/ (both renders, their buffers and error maps), DIR/charts/,
// DIR/sequence.mp4 and DIR/sequence.webm. The report's images are those of the frame with the
// largest beauty.flip.
report::SceneReport runSequence(LoadedScene& scene, Devices& devices, ReferenceCache& cache,
                                const SequenceRun& run, const std::filesystem::path& dir);

}  // namespace twinrender::app
