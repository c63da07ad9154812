#include "realtime/per_set.h"

#include <chrono>
#include <cmath>
#include <memory>
#include <span>

#include "core/body_sphere.h"
#include "core/stage_table.h"
#include "realtime/body_sphere_lod.h"
#include "realtime/gl/error.h"
#include "realtime/gpu_scene.h"
#include "realtime/particle_set_key.h"
#include "realtime/per_set_gpu.h"

namespace twinrender::realtime {

void PerSetWork::afterFrame(core::Frame&) {}

std::vector<std::string> perSetStages() {
    std::vector<std::string> out;
    for (const core::StageInfo& s : core::stageTable())
        if (s.cadence == core::StageCadence::Set && s.renderer == "realtime")
            out.emplace_back(s.key);
    return out;
}

double nearReach(const core::Camera& camera) {
    const double t = camera.tanHalfFovY();
    return camera.settings().near *
           std::sqrt(1.0 + t * t * (1.0 + camera.aspect() * camera.aspect()));
}

namespace {

// per_set = "gpu" (per_set_gpu.h): the particles' attributes uploaded once per set, the per-set
// answers computed and the draw lists packed by compute passes; the draws take their counts
// from indirect commands. Times "upload" (the staging's wall clock) and the GPU stages (timer
// queries, read after the frame), counts "per_set_builds" and "body_spheres".
// particles.body_sphere_pixels: the bodies drawn as one sphere are chosen on the CPU as the CPU
// path chooses them; the packing keeps every particle (the marks are reused across frames and
// know nothing of the camera's distance), and a mask of the replaced bodies, one word per body,
// makes the passes leave their particles out: the impostor programs drop them, the gradient
// gather skips their kernels, and REPLACED counts them for particles_drawn and droplets.
class GpuPerSetWork final : public PerSetWork {
  public:
    PerSetDraws prepare(ProgramCache& programs, const core::RenderInput& in,
                        const core::Camera& camera, const Settings& settings,
                        const std::function<void(std::size_t)>& checkRecords,
                        core::Frame& frame) override {
        const core::ParticleSet& ps = in.particles.particles;
        checkRecords(ps.size());
        // Timed with the upload, as on the CPU path: the level-set spheres of a new set, then
        // a test a body.
        const auto chooseStart = std::chrono::steady_clock::now();
        const BodySphereChoice bodySpheres = chooseBodySpheres(in, camera, settings.particles);
        const double chooseMs = std::chrono::duration<double, std::milli>(
                                    std::chrono::steady_clock::now() - chooseStart)
                                    .count();
        PerSetRequest request = perSetRequest(settings);
        // As on the CPU path: the culling counts on every particle being drawn, and a replaced
        // body whose supports reach another body's may have hidden some of its particles. The
        // culling's answers stay kept; the marks, made with culling or without, are redone when
        // this changes (GpuPerSet::pack compares what they were made with).
        if (bodySpheres.touchesOthers) request.cull = false;
        const bool built = mPerSet.update(
            programs, ps, request,
            in.particles.hasNormals ? std::span<const core::BodyInfo>() : in.particles.bodies);
        frame.counters["per_set_builds"] = built ? 1.0 : 0.0;
        frame.timingsMs["upload"] = mPerSet.uploadMs() + chooseMs;
        mPerSet.pack(programs, {in.scene.camera.position, nearReach(camera)});
        frame.counters["body_spheres"] = static_cast<double>(bodySpheres.drawn.size());
        mBodiesReplaced = !bodySpheres.drawn.empty() && ps.size() > 0;
        if (mBodiesReplaced) {
            uploadBodyMask(bodySpheres);
            mPerSet.countReplaced(programs, mBodyMask);
        }
        gl::checkErrors("per-set compute passes");
        PerSetDraws out;
        if (ps.size() == 0) {
            mEmpty = gl::Buffer::zeros(16);
            out.particles = &mEmpty;
            return out;
        }
        if (mBodiesReplaced) {
            const std::vector<GpuParticle> packed =
                packBodySpheres(bodySpheres.drawn, in.particles.bodies, in.scene.camera.position);
            mBodySphereRecords = gl::Buffer::of(std::span<const GpuParticle>(packed));
            out.bodySpheres = SceneBuffers::BodySpheres{&mBodySphereRecords, {packed.size()}};
            out.bodyMask = SceneBuffers::BodyMask{
                .words = &mBodyMask,
                .reachesOthers = !replacedApart(bodySpheres, settings.particles)};
        }
        out.particles = &mPerSet.particles();
        out.draw = {0, &mPerSet.drawCommands(), GpuPerSet::particleDrawOffset()};
        if (mPerSet.ellipsoidsDrawn()) out.ellipsoids = &mPerSet.ellipsoids();
        if (mPerSet.dropletsApart())
            out.droplets = SceneBuffers::Droplets{
                &mPerSet.dropletEllipsoids(),
                {0, &mPerSet.drawCommands(), GpuPerSet::dropletDrawOffset()}};
        if (usesKernels(settings)) out.gradientGrid = &mPerSet;
        return out;
    }

    void afterFrame(core::Frame& frame) override {
        for (const auto& [stage, ms] : mPerSet.takeTimings()) frame.timingsMs[stage] = ms;
        mPerSet.afterFrame();
        double drawn = mPerSet.drawnCount(), droplets = mPerSet.dropletCount();
        if (mBodiesReplaced) {
            // REPLACED's counts (shaders/body_mask.glsl): what the BODY_MASK programs dropped.
            const std::vector<std::uint32_t> replaced = mBodyMask.read<std::uint32_t>(0, 2);
            drawn -= replaced[0];
            droplets -= replaced[1];
        }
        frame.counters["particles_drawn"] = drawn;
        frame.counters["droplets"] = droplets;
        // normal = "gradient": the gradient is gathered through the grid, no kernel splatted.
    }

  private:
    // particles.body_sphere_pixels: this frame's bodies drawn as one sphere (0: off, none).
    BodySphereChoice chooseBodySpheres(const core::RenderInput& in, const core::Camera& camera,
                                       const ParticleSettings& settings) {
        if (settings.bodySpherePixels <= 0.0) return {};
        const core::ParticleSet& ps = in.particles.particles;
        const std::vector<core::BodySphere>& spheres = mBodySpheres.get(
            ps, [&] { return core::bodySpheres(in.particles, settings.surfaceLevel); },
            settings.surfaceLevel, std::span<const glm::vec3>(ps.glow));
        return realtime::chooseBodySpheres(spheres, in.particles.bodies.size(), camera,
                                           settings.bodySpherePixels);
    }

    // Whether every surface point the G-buffer may hold lies within its own body's supports'
    // bounding sphere (BodySphereChoice's reach) and those of the replaced bodies meet no other
    // body's: spheres within their particles' supports (not min_pixels' splats, not ellipsoids,
    // whose axes may reach further; the droplets' ellipsoids are fitted to their level set).
    static bool replacedApart(const BodySphereChoice& choice, const ParticleSettings& settings) {
        return !choice.touchesOthers && settings.minPixels == 0.0 &&
               settings.shape == ParticleShape::Sphere && settings.radiusScale <= 2.0;
    }

    // shaders/body_mask.glsl: REPLACED's two counts (zero) and padding, then a word per body.
    void uploadBodyMask(const BodySphereChoice& choice) {
        std::vector<std::uint32_t> words(4 + choice.replaced.size(), 0);
        for (std::size_t b = 0; b < choice.replaced.size(); ++b)
            words[4 + b] = choice.replaced[b] ? 1 : 0;
        mBodyMask = gl::Buffer::of(std::span<const std::uint32_t>(words));
    }

    GpuPerSet mPerSet;
    gl::Buffer mEmpty;  // an empty set's particle buffer (a binding is always valid)
    // The bodies' level-set spheres (particles.body_sphere_pixels), and their inputs: the surface
    // level and the glow they average (as per_set_cpu.cpp keeps them).
    SetCache<std::vector<core::BodySphere>, double, std::span<const glm::vec3>> mBodySpheres;
    bool mBodiesReplaced = false;              // this frame draws some body as its sphere
    gl::Buffer mBodyMask, mBodySphereRecords;  // this frame's mask and spheres
};

}  // namespace

std::unique_ptr<PerSetWork> makeGpuPerSetWork() {
    return std::make_unique<GpuPerSetWork>();
}

}  // namespace twinrender::realtime
