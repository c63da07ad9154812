// A renderer of the user's own, run as a command once per frame (docs/external.md, "The
// protocol"): for each frame twinrender exports the scene into the frame's own working folder,
// writes a request (request.json, versioned) naming the exported files and where the image and
// an optional timings file must go, and runs the command there with the request's path as its
// argument, within a time limit. The image it writes (an EXR with whichever AOV channels the
// renderer has) is the frame; compare::computeMetrics gives every metric its channels allow.
#pragma once

#include <filesystem>
#include <string>

#include "app/render_job.h"
#include "core/renderer.h"

namespace twinrender::app {

// The request's format and version (request.json's "format", "version").
inline constexpr const char* REQUEST_FORMAT = "twinrender-request";
inline constexpr int REQUEST_VERSION = 1;

class ExternalRenderer final : public core::Renderer {
  public:
    // `scene`: the loaded scene the frames come from (its reference settings name the surface
    // level the export states); it must outlive the renderer.
    ExternalRenderer(ExternalSettings settings, const LoadedScene& scene);

    // Exports the frame, runs the command, reads its image. Throws core::InputError naming the
    // command, the frame and what was wrong: the command not found or not executable, a non-zero
    // exit (the last lines of its standard error), the time limit passed (its process group is
    // ended), no image, an image of another size or without R, G, B, NaN or an infinity in a
    // channel (but +inf in Z); core::Cancelled when interrupted (the command ended too).
    core::Frame render(const core::RenderInput& input) override;

  private:
    ExternalSettings mSettings;
    const LoadedScene& mScene;
};

}  // namespace twinrender::app
