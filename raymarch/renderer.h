// The reference raymarcher (docs/design.md, "The reference raymarcher"): the exact level set of the
// particles' colour field (surface_tracer.h), shaded with the shared model, written as the
// AOV image. Tiles run in parallel on the caller's oneTBB arena; every pixel is computed on
// its own, so the image is bit-identical for any thread count, and for any split of the frame
// into parts (core/frame_part.h) once they are joined.
#pragma once

#include "core/renderer.h"
#include "raymarch/embree_device.h"
#include "raymarch/settings.h"

namespace twinrender::raymarch {

class Renderer final : public core::Renderer {
  public:
    // The device must outlive the renderer.
    Renderer(const EmbreeDevice& device, const Settings& settings);

    // Builds the acceleration structures of the particles (the "build" stage, part of
    // "total"), then traces the tiles ("trace": surfaces and shadow rays, "shade"), those of
    // `input.part` alone when it is not the whole frame. Calls `progress` from worker
    // threads, at most once per tile.
    core::Frame render(const core::RenderInput& input) override;

  private:
    const EmbreeDevice& mDevice;
    Settings mSettings;
};

}  // namespace twinrender::raymarch
