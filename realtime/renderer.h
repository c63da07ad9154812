// The real-time renderer: sphere impostors, Screen-Space Surface Smoothing, logarithmic or
// reversed depth, shadow maps (DESIGN.md, "Real-time"). One Renderer per GL context; it
// compiles its programs on first use and keeps them for later renders.
#pragma once

#include <memory>
#include <vector>

#include "core/frame.h"
#include "core/particles.h"
#include "core/scene.h"
#include "core/texture.h"
#include "realtime/settings.h"

namespace twinrender::realtime {

namespace gl {
class Context;
}

struct RenderResult {
    // The AOV image (linear beauty without bloom, Z = eye depth, ...), renderer "realtime",
    // device = GL_RENDERER, settings by dotted key, counters (particles_drawn,
    // occlusion_spheres), timingsMs: total, cull, upload, shadow, gbuffer, ssss, shade, post,
    // readback (GPU timer queries for the five passes; wall clock for the rest; a stage that
    // did not run reports 0) and compile (not part of total).
    core::Frame frame;
    // What the PNG shows: bloom (when enabled) and core's tonemapper, sRGB R, G, B in [0, 1],
    // top row first. Pass it to core::writeFrame as `display`.
    core::Image display;
};

class Renderer {
  public:
    // The context must be current on the calling thread and outlive the renderer.
    explicit Renderer(const gl::Context& context);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Renders the scene's camera view. `materials` in Scene::materials order
    // (core::loadMaterials). Throws core::InputError when the image or shadow map exceeds the
    // device's limits, gl::Error (naming the pass) when GL fails.
    RenderResult render(const core::Scene& scene, const core::SceneParticles& particles,
                        const std::vector<core::Material>& materials, const Settings& settings);

    // Hands a finished result back (optional): the next render of the same size writes its
    // images into that memory instead of fresh pages. A frame loop at 1280 x 720 otherwise
    // faults in ~65 MB of new pages per frame, 60-100 ms on the 2-core CPU machines.
    void recycle(RenderResult&& old);

  private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

}  // namespace twinrender::realtime
