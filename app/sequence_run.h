// Sequences in the commands that render (README, "Sequences"): `render SCENE --frames A:B`
// writes each frame's renders into a numbered folder, and `run` renders every frame of a
// sequence scene with both renderers (the reference through the cache of app/reference_cache.h,
// keyed by the frame), compares each pair, measures the temporal error of each consecutive
// pair against the truth (compare/temporal_error.h), and writes the charts, the side-by-side
// video (app/video_encoder.h) and the scene's report, whose metrics summarise the frames
// (compare/sequence_summary.h). Every frame is a new particle set for the real-time renderer.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "app/reference_cache.h"
#include "app/render_job.h"
#include "compare/baseline.h"
#include "compare/report.h"
#include "compare/thresholds.h"

namespace twinrender::app {

// The overrides of `--frames A:B` (or A:B:STEP, or one frame A): sequence.first, sequence.last
// and sequence.step. Throws core::InputError for anything else.
std::vector<std::string> framesOverrides(const std::string& frames);

// The folder name of a frame, zero-padded to four digits ("0007"; "-0003" below zero).
std::string frameFolder(std::int64_t frame);

// Moves a loaded scene to a frame of its sequence (camera, files, moving bodies) and builds its
// particles anew.
void setFrame(LoadedScene& scene, std::int64_t frame);

// Reads every particle file of every frame of the scene's sequence but its current one (read by
// loadScene), so that an unreadable frame is bad input before any rendering: throws
// core::InputError naming the frame and the reader's message (which names the file).
void checkSequenceFiles(const LoadedScene& scene);

// `render --frames`: every frame of the scene's range with each renderer, into
// DIR/<frameFolder>/<renderer>.exr|png|json. Prints a line per render.
void renderFrames(LoadedScene& scene, const std::vector<std::string>& renderers, Devices& devices,
                  const std::filesystem::path& dir);

struct SequenceRun {
    std::vector<std::string> overrides;  // the run's --set, for the reference cache's keys
    compare::Bounds bounds;
    const compare::Baseline* baseline = nullptr;
    double ppd = 67.0;
    double flipOver = 0.5;
};

// `run` on a sequence scene: see above. Writes DIR/frames/<frameFolder>/ (both renders, their
// buffers and error maps), DIR/charts/, DIR/sequence.mp4 and DIR/sequence.webm. The report's
// images are those of the frame with the largest beauty.flip.
compare::SceneReport runSequence(LoadedScene& scene, Devices& devices, ReferenceCache& cache,
                                 const SequenceRun& run, const std::filesystem::path& dir);

}  // namespace twinrender::app
