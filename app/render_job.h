// Loading a scene and rendering it with any renderer: what every command that renders
// shares. All input is read and checked before any rendering starts.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/frame.h"
#include "core/particles.h"
#include "core/renderer.h"
#include "core/scene.h"
#include "core/texture.h"
#include "raymarch/settings.h"
#include "realtime/settings.h"

namespace twinrender {
namespace raymarch {
class EmbreeDevice;
}
namespace realtime {
class Device;
namespace gl {
class Context;
}
}  // namespace realtime
}  // namespace twinrender

namespace twinrender::app {

// A scene with everything every renderer needs, validated.
struct LoadedScene {
    core::Scene scene;
    raymarch::Settings raymarch;
    realtime::Settings realtime;
    std::vector<core::Material> materials;
    core::SceneParticles particles;
};

// Reads the scene, applies the overrides, parses every renderer section (unknown keys are
// errors), loads the textures and builds the particles (of a sequence's first frame, after
// reading every frame's files once).
LoadedScene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides);

// The external renderer (app/external_renderer.h): a command of the user's own run once per
// frame.
struct ExternalSettings {
    // Run by /bin/sh -c in the frame's folder, with the request's path appended as its last
    // argument.
    std::string command;
    double timeoutSeconds = 600.0;  // per frame, > 0
    // Each frame's working folder is ROOT/<scene>/external/<frame> (four digits), made anew: ROOT
    // the command's output folder.
    std::filesystem::path root;
    // `run --test-images DIR`: the folder of images rendered earlier, one per scene and frame,
    // that makeRenderer's "images" reads in the command's place (app/test_images.h).
    std::filesystem::path images;
};

// When the per-set self-check runs before a command's first real-time frame
// (app/per_set_check.h).
struct SelfCheckPolicy {
    bool force = false;  // --self-check: on every device (llvmpipe too), the verdict not remembered
    // --cache: the folder where the verdict is remembered per device, driver and build (empty:
    // once per process)
    std::filesystem::path cache{};
};

// The devices the renderers run on, each created on first use (a command that renders no
// real-time frame opens no GL context) and kept for the command's life.
class Devices {
  public:
    explicit Devices(bool requireGpu = false, SelfCheckPolicy selfCheck = {});
    ~Devices();
    Devices(const Devices&) = delete;
    Devices& operator=(const Devices&) = delete;

    const raymarch::EmbreeDevice& embree();
    // The GL context (throws core::InputError when none can be had) and the compiled programs
    // and caches that the real-time renderers made on it share.
    realtime::Device& realtime();
    // realtime(), its per-set self-check run first where the policy asks for one and none has
    // run on it (checkPerSetOnce, with `scene` drawn small): every real-time renderer of a
    // command is made through this.
    realtime::Device& realtimeFor(const LoadedScene& scene);
    // The GL context realtime() made (made by it when there is none yet).
    const realtime::gl::Context& glContext();
    // The external renderer's command (makeRenderer's "external"); set by the command line.
    void setExternal(ExternalSettings settings) { mExternal = std::move(settings); }
    const ExternalSettings& external() const { return mExternal; }

  private:
    bool mRequireGpu;
    SelfCheckPolicy mSelfCheck;
    bool mPerSetChecked = false;
    ExternalSettings mExternal;
    std::unique_ptr<raymarch::EmbreeDevice> mEmbree;
    std::unique_ptr<realtime::gl::Context> mContext;
    std::unique_ptr<realtime::Device> mRealtime;
};

// The renderers by name, in the order `render --renderer both` runs them.
const std::vector<std::string>& rendererNames();

// The renderer `name` ("raymarch", "realtime", "external": devices.external()'s command, or
// "images": the images of devices.external().images) with the scene's settings for it.
std::unique_ptr<core::Renderer> makeRenderer(std::string_view name, Devices& devices,
                                             const LoadedScene& scene);

// Renders the scene, with a progress bar ("<scene>: <name>") on a terminal while the renderer
// reports progress. `exactSurface`: the reference's AOV image, for the error split
// (core::RenderInput::exactSurface); `part`: the part of the frame to draw
// (core::RenderInput::part).
core::Frame render(core::Renderer& renderer, std::string_view name, const LoadedScene& scene,
                   const core::Image* exactSurface = nullptr, core::FramePart part = {});
// One frame of a renderer made for it (makeRenderer).
core::Frame render(std::string_view name, Devices& devices, const LoadedScene& scene,
                   const core::Image* exactSurface = nullptr);

// A frame and its cost over several frames: per stage and for the total, the median and the
// fastest. On a machine that other processes share they lengthen some frames and shorten
// none, so the fastest frame is the nearest to the frame's own cost; the median is the typical
// frame under that load.
struct TimedFrame {
    core::Frame frame;                        // the last frame rendered
    std::map<std::string, double> medianMs;   // stage -> median ms, "total" included
    std::map<std::string, double> fastestMs;  // stage -> least ms, "total" included
};

// Renders `frames` (>= 1) frames of the scene with one renderer and takes the median and the
// least of each stage's time. With `warmUp`, one untimed frame first: the driver compiles shader
// variants on first use, and a particle set's first frame does its per-set work (culling, impostor
// radii). The "compile" stage (programs built for the renderer) is not part of a frame's time and
// is left out.
// `exactSurface`: the reference's AOV image, given to the last frame alone (the one returned)
// for the error split (core::RenderInput::exactSurface); its passes run after the frame's
// timings are taken.
TimedFrame renderTimed(std::string_view name, Devices& devices, const LoadedScene& scene,
                       int frames, bool warmUp, const core::Image* exactSurface = nullptr);
// The same for several scenes (or settings of one), their frames rendered in rounds, one frame
// of each in turn, each round starting at another: a change of the machine's load over the
// rounds, or within each, then falls on every scene alike, where one scene's frames after
// another's would give the later ones another load.
// `exactSurfaces`: empty, or one per scene (null: none) for the last round's frames.
std::vector<TimedFrame> renderTimedRounds(
    std::string_view name, Devices& devices, const std::vector<const LoadedScene*>& scenes,
    int frames, bool warmUp, const std::vector<const core::Image*>& exactSurfaces = {});

// Writes DIR/<renderer>.exr|.png|.json for a frame of the scene.
void writeRender(const LoadedScene& scene, const core::Frame& frame,
                 const std::filesystem::path& dir);

}  // namespace twinrender::app
