// The work done once per particle set (normals where a set came without them, impostor radii,
// droplets, culling, field normal models, ellipsoids, the gradient pass's kernels) behind one
// interface with two back ends: the CPU's (oneTBB, cached per set, packed and uploaded;
// per_set_cpu.cpp) and the GPU's (compute passes, per_set_gpu.h). realtime.per_set names the
// back end a frame takes; a device keeps one of each, so renderers sharing it keep their
// answers.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/renderer.h"
#include "realtime/passes.h"
#include "realtime/settings.h"
#include "realtime/shader_library.h"

namespace twinrender::realtime {

class GpuPerSet;

// The stages of the work done once per particle set: core/stage_table.h's with cadence Set (0
// in a frame when they do not run or an unchanged set reuses them). "upload" and, on the GPU,
// "pack" are per frame.
std::vector<std::string> perSetStages();

// A frame's particles as the passes draw them.
struct PerSetDraws {
    const gl::Buffer* particles = nullptr;           // GpuParticle[]
    DrawList draw;                                   // the particles drawn
    const gl::Buffer* ellipsoids = nullptr;          // GpuEllipsoid[] (shape = "ellipsoid")
    std::optional<SceneBuffers::Droplets> droplets;  // droplets drawn apart from spheres
    // particles.body_sphere_pixels: the bodies drawn as one sphere each; on the GPU, whose
    // packing keeps every particle, with the mask of those bodies (SceneBuffers::bodyMask).
    std::optional<SceneBuffers::BodySpheres> bodySpheres;
    std::optional<SceneBuffers::BodyMask> bodyMask;
    // normal = "gradient": the kernels to splat (the CPU's), or the grid to gather the gradient
    // through (the GPU's).
    const gl::Buffer* kernels = nullptr;  // GpuKernel[]
    DrawList kernelDraw;
    GpuPerSet* gradientGrid = nullptr;
};

class PerSetWork {
  public:
    virtual ~PerSetWork() = default;
    // The draws of a frame of `in` seen by `camera`, the per-set answers built anew where the
    // set or the settings they depend on changed. Times its stages (perSetStages(), "upload",
    // "pack") and counts particles_drawn, droplets, body_spheres, kernels_splatted and
    // per_set_builds into `frame`; calls `checkRecords(n)` before it makes n packed particles'
    // records (throws where the device cannot hold them). The buffers live until the next
    // prepare().
    virtual PerSetDraws prepare(ProgramCache& programs, const core::RenderInput& in,
                                const core::Camera& camera, const Settings& settings,
                                const std::function<void(std::size_t)>& checkRecords,
                                core::Frame& frame) = 0;
    // After the frame has been drawn: what the frame reads back (the GPU's stage times and
    // counts).
    virtual void afterFrame(core::Frame& frame);
};

std::unique_ptr<PerSetWork> makeCpuPerSetWork();
std::unique_ptr<PerSetWork> makeGpuPerSetWork();

// Occlusion culling assumes that every ray starts outside all spheres. Rays start at the near
// plane; every point of the frustum in front of it lies within nearReach of the eye, so no
// sphere reaching into that ball means the near plane cannot cut a body open.
double nearReach(const core::Camera& camera);

}  // namespace twinrender::realtime
