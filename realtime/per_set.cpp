#include "realtime/per_set.h"

#include <cmath>
#include <memory>
#include <span>

#include "core/stage_table.h"
#include "realtime/gl/error.h"
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
// queries, read after the frame), counts "per_set_builds".
class GpuPerSetWork final : public PerSetWork {
  public:
    PerSetDraws prepare(ProgramCache& programs, const core::RenderInput& in,
                        const core::Camera& camera, const Settings& settings,
                        const std::function<void(std::size_t)>& checkRecords,
                        core::Frame& frame) override {
        const core::ParticleSet& ps = in.particles.particles;
        checkRecords(ps.size());
        const PerSetRequest request = perSetRequest(settings);
        const bool built = mPerSet.update(
            programs, ps, request,
            in.particles.hasNormals ? std::span<const core::BodyInfo>() : in.particles.bodies);
        frame.counters["per_set_builds"] = built ? 1.0 : 0.0;
        frame.timingsMs["upload"] = mPerSet.uploadMs();
        mPerSet.pack(programs, {in.scene.camera.position, nearReach(camera)});
        gl::checkErrors("per-set compute passes");
        PerSetDraws out;
        if (ps.size() == 0) {
            mEmpty = gl::Buffer::zeros(16);
            out.particles = &mEmpty;
            return out;
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
        frame.counters["particles_drawn"] = mPerSet.drawnCount();
        frame.counters["droplets"] = mPerSet.dropletCount();
        // normal = "gradient": the gradient is gathered through the grid, no kernel splatted.
    }

  private:
    GpuPerSet mPerSet;
    gl::Buffer mEmpty;  // an empty set's particle buffer (a binding is always valid)
};

}  // namespace

std::unique_ptr<PerSetWork> makeGpuPerSetWork() {
    return std::make_unique<GpuPerSetWork>();
}

}  // namespace twinrender::realtime
