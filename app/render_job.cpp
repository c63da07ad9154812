#include "app/render_job.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdlib>
#include <utility>
#include <vector>

#include "app/external_renderer.h"
#include "app/interruption.h"
#include "app/per_set_check.h"
#include "app/progress.h"
#include "app/test_images.h"
#include "core/error.h"
#include "core/particle_file.h"
#include "raymarch/embree_device.h"
#include "raymarch/renderer.h"
#include "realtime/gl/context.h"
#include "realtime/renderer.h"
#include "report/study_summary.h"

namespace twinrender::app {

namespace {

// Reads every particle file of every frame of the scene's sequence but its current one (read by
// loadScene), so that an unreadable frame is bad input before any rendering: throws
// core::InputError naming the frame and the reader's message (which names the file).
void checkSequenceFiles(const LoadedScene& s) {
    if (!s.scene.sequence) return;
    for (const core::BodyDesc& b : s.scene.bodies)
        for (const core::FrameFile& f : b.frameFiles) {
            if (f.number == s.scene.frame) continue;
            try {
                core::readParticleFile(f.path);
            } catch (const core::InputError& e) {
                throw core::InputError(fmt::format(
                    "{}: body '{}': frame {} of the sequence {} cannot be read: {}", b.where,
                    b.name, f.number, b.pattern.filename().string(), e.what()));
            }
        }
}

}  // namespace

LoadedScene loadScene(const std::filesystem::path& file,
                      const std::vector<std::string>& overrides) {
    LoadedScene s;
    s.scene = core::loadScene(file, overrides);
    s.raymarch = raymarch::parseSettings(s.scene.raymarch);
    s.realtime = realtime::parseSettings(s.scene.realtime);
    // [compare.thresholds] belongs to compare/; its keys are read there.
    s.scene.compare.keysUnder("thresholds");
    s.scene.compare.checkAllRead();
    s.materials = core::loadMaterials(s.scene);
    s.particles = core::buildParticles(s.scene);
    checkSequenceFiles(s);
    return s;
}

Devices::Devices(bool requireGpu, SelfCheckPolicy selfCheck)
    : mRequireGpu(requireGpu), mSelfCheck(std::move(selfCheck)) {}

Devices::~Devices() = default;

const raymarch::EmbreeDevice& Devices::embree() {
    if (!mEmbree) mEmbree = std::make_unique<raymarch::EmbreeDevice>();
    return *mEmbree;
}

realtime::Device& Devices::realtime() {
    if (!mRealtime) {
        // TWINRENDER_GL_DEBUG=1: a debug context, on which any GL error the driver logs fails
        // the frame (the tests run the tool so).
        const char* debug = std::getenv("TWINRENDER_GL_DEBUG");
        mContext = std::make_unique<realtime::gl::Context>(realtime::gl::ContextOptions{
            .requireGpu = mRequireGpu, .debug = debug && std::string_view(debug) == "1"});
        mRealtime = std::make_unique<realtime::Device>(*mContext);
    }
    return *mRealtime;
}

realtime::Device& Devices::realtimeFor(const LoadedScene& scene) {
    realtime::Device& device = realtime();
    if (!mPerSetChecked) {
        mPerSetChecked = true;
        checkPerSetOnce(device, *mContext, scene, mSelfCheck);
    }
    return device;
}

const realtime::gl::Context& Devices::glContext() {
    realtime();
    return *mContext;
}

const std::vector<std::string>& rendererNames() {
    static const std::vector<std::string> names = {"raymarch", "realtime"};
    return names;
}

std::unique_ptr<core::Renderer> makeRenderer(std::string_view name, Devices& devices,
                                             const LoadedScene& s) {
    if (name == "raymarch")
        return std::make_unique<raymarch::Renderer>(devices.embree(), s.raymarch);
    if (name == "realtime")
        return std::make_unique<realtime::Renderer>(devices.realtimeFor(s), s.realtime);
    if (name == "external") return std::make_unique<ExternalRenderer>(devices.external(), s);
    if (name == "images") return std::make_unique<TestImages>(devices.external().images);
    throw core::InputError(fmt::format("no renderer named '{}'; the renderers are {}", name,
                                       fmt::join(rendererNames(), ", ")));
}

core::Frame render(core::Renderer& renderer, std::string_view name, const LoadedScene& s,
                   const core::Image* exactSurface, core::FramePart part) {
    throwIfInterrupted();
    Progress progress(part.whole() ? fmt::format("{}: {}", s.scene.name, name)
                                   : fmt::format("{}: {} part {}/{}", s.scene.name, name,
                                                 part.index, part.count));
    core::Frame frame = renderer.render({.scene = s.scene,
                                         .particles = s.particles,
                                         .materials = s.materials,
                                         .progress = [&](double f) { progress.update(f); },
                                         .cancel = interruptFlag(),
                                         .exactSurface = exactSurface,
                                         .part = part});
    progress.finish();
    throwIfInterrupted();
    return frame;
}

core::Frame render(std::string_view name, Devices& devices, const LoadedScene& s,
                   const core::Image* exactSurface) {
    return render(*makeRenderer(name, devices, s), name, s, exactSurface);
}

std::vector<TimedFrame> renderTimedRounds(std::string_view name, Devices& devices,
                                          const std::vector<const LoadedScene*>& scenes, int frames,
                                          bool warmUp,
                                          const std::vector<const core::Image*>& exactSurfaces) {
    std::vector<std::unique_ptr<core::Renderer>> renderers;
    for (const LoadedScene* s : scenes) {
        renderers.push_back(makeRenderer(name, devices, *s));
        if (warmUp) render(*renderers.back(), name, *s);
    }
    std::vector<TimedFrame> timed(scenes.size());
    std::vector<std::map<std::string, std::vector<double>>> times(scenes.size());
    const std::size_t n = scenes.size(), rounds = static_cast<std::size_t>(std::max(frames, 1));
    for (std::size_t f = 0; f < rounds; ++f)
        // Each round starts further along, so that each scene takes another place in each.
        for (std::size_t k = 0; k < n; ++k) {
            const std::size_t i = (k + f * n / rounds) % n;
            const bool last = f + 1 == rounds;
            timed[i].frame = render(*renderers[i], name, *scenes[i],
                                    last && i < exactSurfaces.size() ? exactSurfaces[i] : nullptr);
            for (const auto& [stage, ms] : timed[i].frame.timingsMs)
                if (stage != "compile") times[i][stage].push_back(ms);
        }
    for (std::size_t i = 0; i < scenes.size(); ++i)
        for (const auto& [stage, v] : times[i]) {
            timed[i].medianMs[stage] = report::median(v);
            timed[i].fastestMs[stage] = *std::min_element(v.begin(), v.end());
        }
    return timed;
}

TimedFrame renderTimed(std::string_view name, Devices& devices, const LoadedScene& s, int frames,
                       bool warmUp, const core::Image* exactSurface) {
    return std::move(
        renderTimedRounds(name, devices, {&s}, frames, warmUp, {exactSurface}).front());
}

void writeRender(const LoadedScene& s, const core::Frame& frame, const std::filesystem::path& dir) {
    nlohmann::json extra;
    extra["scene"] = s.scene.name;
    extra["scene_file"] = s.scene.file.string();
    extra["camera"] = {
        {"position",
         {s.scene.camera.position.x, s.scene.camera.position.y, s.scene.camera.position.z}},
        {"target", {s.scene.camera.target.x, s.scene.camera.target.y, s.scene.camera.target.z}},
        {"fov_y_deg", s.scene.camera.fovYDeg},
        {"near", s.scene.camera.near},
        {"far", s.scene.camera.far},
        {"exposure", s.scene.camera.exposure}};
    core::writeFrame(frame, dir, extra);
}

}  // namespace twinrender::app
