// The one interface of a renderer (CONTRIBUTING.md, "House style"): the reference raymarcher, the
// real-time renderer and any third one take the same inputs and return the same Frame, so the
// commands, sweeps and studies treat them alike. A renderer is constructed with its device and its
// typed settings; everything a render reads about the scene comes in through RenderInput.
#pragma once

#include <atomic>
#include <functional>
#include <string_view>
#include <vector>

#include "core/frame.h"
#include "core/particles.h"
#include "core/scene.h"
#include "core/texture.h"

namespace twinrender::core {

// What one render reads. The references must outlive the render() call only.
struct RenderInput {
    const Scene& scene;
    const SceneParticles& particles;
    const std::vector<Material>& materials;  // in Scene::materials order (loadMaterials)
    // Optional: called with the finished fraction in [0, 1], possibly from worker threads.
    std::function<void(double)> progress = {};
    // Optional: when it becomes true, the render stops at its next tile or pass and throws
    // core::Cancelled (core/cancellation.h).
    const std::atomic<bool>* cancel = nullptr;
    // Optional: the reference's AOV image of the same view. A renderer that can shades it
    // too, to say where its own image's error comes from, and fills Frame::split.
    const Image* exactSurface = nullptr;
    // Optional: draw only this part of the frame (core/frame_part.h; `render --tiles K/N`). The
    // frame's images hold the part's rows of pixels alone, and Frame::part records which part
    // it is. A renderer that draws whole frames only refuses a part (requireWholeFrame).
    FramePart part{};
};

// Throws InputError when `input` asks for a part of the frame: for a renderer (`renderer`, its
// name) that draws whole frames only.
void requireWholeFrame(const RenderInput& input, std::string_view renderer);

class Renderer {
  public:
    virtual ~Renderer();

    // Renders the scene's camera view: the AOV image, the display image, counters and stage
    // timings (Frame). Throws core::InputError when the scene exceeds what the device can do.
    virtual Frame render(const RenderInput& input) = 0;

    // Hands a finished frame back (optional): a renderer may write the next frame of the same
    // size into its memory instead of fresh pages. The default drops it.
    virtual void recycle(Frame&& /*frame*/) {}
};

}  // namespace twinrender::core
