// The real-time renderer: sphere impostors, Screen-Space Surface Smoothing, logarithmic or
// reversed depth, shadow maps (docs/design.md, "The real-time renderer"). A frame is five steps:
// check the device's limits, compile the programs, upload the scene, run the passes (passes.h),
// read back the AOV image.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/renderer.h"
#include "realtime/particle_set_key.h"
#include "realtime/settings.h"

namespace twinrender::realtime {

namespace gl {
class Context;
}

struct DeviceState;

// The GL context as real-time renderers use it: its limits, the compiled programs (the driver
// compiles a program's variants on its first draws: hundreds of ms on llvmpipe), the answers
// kept per particle set (occlusion culling, field normals) and the read-back memory. Every
// renderer made on one Device shares them, so renderers with other settings (a sweep's
// combinations, a study's points) compile a program and cull a particle set once. Use it on
// the context's thread.
class Device {
  public:
    // The context must be current on the calling thread and outlive the device.
    explicit Device(const gl::Context& context);
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    // The names of the programs compiled on it so far (program_variants.h names them alike).
    std::vector<std::string> programNames() const;

    // The per-set self-check's verdict on this device (self_check.h's selfCheck, which app/
    // runs once per device, driver and build): passed, or failed with a summary (the checks
    // that failed, the first stage apart). After a failure, a renderer whose settings ask for
    // per_set = "gpu" runs the CPU's per-set work (per_set_fallback) or keeps the GPU's; either
    // way its frames say so in frame.device and counters.per_set_fallback (1 when it fell back,
    // 0 when it kept the GPU's).
    struct PerSetCheck {
        bool passed = true;
        std::string summary{};
    };
    void setPerSetCheck(PerSetCheck check) { mPerSetCheck = std::move(check); }
    const std::optional<PerSetCheck>& perSetCheck() const { return mPerSetCheck; }

  private:
    friend class Renderer;
    std::unique_ptr<DeviceState> mState;
    std::optional<PerSetCheck> mPerSetCheck;
};

class Renderer final : public core::Renderer {
  public:
    // The device must outlive the renderer.
    Renderer(Device& device, const Settings& settings);

    // The AOV image (linear beauty without bloom, Z = eye depth, ...), the display image (bloom
    // when enabled, then core's tonemapper), renderer "realtime", device = GL_RENDERER,
    // settings by dotted key, counters (particles_drawn, kernels_splatted, occlusion_spheres,
    // point_lights, body_spheres), timingsMs: total, radius, anisotropy, cull, upload, shadow,
    // gbuffer, normals, ssss, ao, emissive, shade, post, readback (GPU timer queries for the
    // passes; wall clock for the rest; a stage that did not run reports 0) and compile (not part of
    // total). Never calls `progress`. Throws core::InputError when the image or shadow map exceeds
    // the device's limits, gl::Error (naming the pass) when GL fails.
    core::Frame render(const core::RenderInput& input) override;

    // The next render of the same size on this device writes its images into the old
    // frame's memory instead of fresh pages. A frame loop at 1280 x 720 otherwise faults in
    // ~65 MB of new pages per frame, 60-100 ms on the 2-core CPU machines.
    void recycle(core::Frame&& old) override;

  private:
    // Applies the device's per-set self-check (Device::PerSetCheck) to mSettings once it has
    // failed: per_set = "gpu" becomes "cpu" where per_set_fallback, and mPerSetNote says so.
    void settlePerSet();
    struct PerSetNote {
        bool fellBack = false;
        std::string text{};  // added to frame.device
    };

    Device& mOwner;
    DeviceState& mDevice;
    Settings mSettings;
    std::optional<PerSetNote> mPerSetNote;
    // The atmosphere's inner radius (core::levelSetRadius of its body at the surface level),
    // kept while the particle set stays the same.
    SetCache<double, std::uint32_t, double> mLevelSetRadius;
};

}  // namespace twinrender::realtime
