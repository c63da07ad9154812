// The reference raymarcher (DESIGN.md, "Reference raymarcher"): the exact level set of the
// particles' colour field (surface_tracer.h), shaded with the shared model, written as the
// AOV image. Tiles run in parallel on the caller's oneTBB arena; every pixel is computed on
// its own, so the image is bit-identical for any thread count.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "core/camera.h"
#include "core/frame.h"
#include "core/particles.h"
#include "core/scene.h"
#include "core/texture.h"
#include "raymarch/embree_device.h"
#include "raymarch/settings.h"
#include "raymarch/surface_tracer.h"

namespace twinrender::raymarch {

class Renderer {
public:
    // Builds the acceleration structures (the "build" stage). The references must outlive
    // the renderer.
    Renderer(const EmbreeDevice& device, const core::Scene& scene,
             const core::SceneParticles& particles, const std::vector<core::Material>& materials,
             const Settings& settings);
    ~Renderer();

    // Renders the AOV image. `progress` (may be empty) is called with the finished fraction,
    // from worker threads, at most once per tile.
    core::Frame render(const std::function<void(double)>& progress = {}) const;

private:
    const core::Scene& mScene;
    const core::SceneParticles& mParticles;
    const std::vector<core::Material>& mMaterials;
    Settings mSettings;
    core::Camera mCamera;
    SurfaceTracer mTracer;
};

}  // namespace twinrender::raymarch
