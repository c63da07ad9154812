// The per-set self-check a command runs before its first real-time frame, so that no driver
// draws a silently wrong image: the scene, drawn small, through both per-set paths
// (realtime/self_check.h's selfCheck). `render`, `run`, `sweep` and `study` run it once per
// device, driver and build on every device but a software rasteriser (on which CI runs the
// GPU path's own tests), and on any device with --self-check. Where the paths disagree, the
// real-time renderers of the command run the CPU's per-set work (realtime.per_set_fallback),
// the terminal says so, and so does every frame's device line (its JSON, the report's
// Devices table).
#pragma once

#include <string>

#include "app/render_job.h"

namespace twinrender::realtime::gl {
class Context;
}

namespace twinrender::app {

// Runs the self-check on `device` (made on `context`) with `scene` drawn at 160 x 120, where
// `policy.force` or the device is not a software rasteriser; takes the verdict from
// policy.cache where that holds one for this device (GL_RENDERER), driver (GL_VERSION) and
// build (realtimeBuildIdentity()) and --self-check did not force a new one, and writes it there
// otherwise. Records the verdict on the device (realtime::Device::setPerSetCheck); prints one
// line when it passes, and where it fails, the table, the first per-set stage apart
// (realtime::perSetStageCheck) and what the renderers do.
void checkPerSetOnce(realtime::Device& device, const realtime::gl::Context& context,
                     const LoadedScene& scene, const SelfCheckPolicy& policy);

}  // namespace twinrender::app
