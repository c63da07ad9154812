// Sequences: a scene whose particles change from frame to frame (file bodies naming a
// sequence of files, generated bodies that move and churn) seen by a camera that may move.
// The [sequence] table (docs/scenes.md, "Sequences"):
//
//   [sequence]
//   first = 0                 # frame numbers; default: the lowest and highest of the first
//   last = 40                 # file body's sequence (a scene of generated bodies sets last)
//   step = 1                  # default: the greatest common step of that sequence's numbers
//   fps = 24.0                # frames per second: time t = frame / fps, and the video's rate
//   camera = "orbit"          # fixed | orbit | keys
//   orbit.degrees_per_frame = 2.0   # or orbit.degrees = 90.0 over the whole range
//   orbit.axis = [0, 0, 1]          # through camera.target; default camera.up
//   [[sequence.keys]]         # camera = "keys": key frames, interpolated (Catmull-Rom)
//   frame = 0
//   position = [...]
//   target = [...]            # default camera.target
//   fov_y_deg = 40.0          # default camera.fov_y_deg
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/parameters.h"
#include "core/scene.h"

namespace twinrender::core {

// Reads [sequence] (`table`, null when the file has none) and its [[sequence.keys]] into
// scene.sequence, lists the files of every body whose path names a sequence, checks that every
// frame of the range has its file and a valid camera, and puts the scene at its first frame.
// A scene with neither a [sequence] table nor a sequence body stays a single frame. Throws
// InputError naming the file, line and key, or the frame and its missing file.
void resolveSequence(Scene& scene, const ParameterTable* table,
                     std::span<const ParameterTable> keys);

// The frame numbers of the scene's range: first, first + step, ... up to last; {scene.frame}
// for a scene that is not a sequence.
std::vector<std::int64_t> sequenceFrames(const Scene& scene);

// The camera at a frame of the sequence (the scene's own camera when it is not one).
CameraSettings cameraAtFrame(const Scene& scene, std::int64_t frame);

// The scene at one frame of its range: its camera, its file bodies' files, frame and time.
// Throws InputError for a frame outside the range.
Scene frameScene(const Scene& scene, std::int64_t frame);

}  // namespace twinrender::core
