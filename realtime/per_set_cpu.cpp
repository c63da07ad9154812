#include <algorithm>
#include <chrono>
#include <iterator>
#include <memory>
#include <span>
#include <vector>

#include "core/derived_attributes.h"
#include "realtime/anisotropy.h"
#include "realtime/body_sphere_lod.h"
#include "realtime/droplets.h"
#include "realtime/field_normal.h"
#include "realtime/gl/error.h"
#include "realtime/gl/pipeline.h"
#include "realtime/gpu_scene.h"
#include "realtime/impostor_radius.h"
#include "realtime/occlusion_culling.h"
#include "realtime/particle_set_key.h"
#include "realtime/per_set.h"
#include "realtime/surface_kernels.h"

namespace twinrender::realtime {

namespace {

using Clock = std::chrono::steady_clock;

double elapsedMs(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Whether no sphere reaches into the near plane's ball (nearReach): culling is exact then.
bool cullingIsExact(const core::ParticleSet& ps, const core::Camera& camera,
                    std::span<const float> radii) {
    const double reach = nearReach(camera);
    for (std::size_t i = 0; i < ps.size(); ++i)
        if (glm::length(glm::dvec3(ps.position[i]) - camera.position()) - radii[i] <= reach)
            return false;
    return true;
}

// The drawn particles: those that may be seen (`culled`, hidden ones removed; empty = all)
// that have a surface of their own (radius > 0). Empty with `nothingDrawn` set when none has.
std::vector<std::uint32_t> withSurface(std::span<const std::uint32_t> culled,
                                       std::span<const float> radii, bool& nothingDrawn) {
    std::vector<std::uint32_t> drawn;
    nothingDrawn = false;
    if (std::find(radii.begin(), radii.end(), 0.0f) == radii.end())
        return {culled.begin(), culled.end()};
    if (culled.empty()) {
        for (std::size_t i = 0; i < radii.size(); ++i)
            if (radii[i] > 0.0f) drawn.push_back(static_cast<std::uint32_t>(i));
    } else {
        for (std::uint32_t i : culled)
            if (radii[i] > 0.0f) drawn.push_back(i);
    }
    nothingDrawn = drawn.empty();
    return drawn;
}

// per_set = "cpu": the particles that may be seen (hidden ones culled where that is exact,
// those without a surface left out) with their impostor radii, ellipsoids and field normal
// models, packed on the CPU and uploaded with the materials and the frame uniforms. Times
// "radius", "kernels", "anisotropy", "field_normals" and "cull" (kept per particle set by the
// device) and "upload" (the rest), counts "particles_drawn" and "per_set_builds".
class CpuPerSetWork final : public PerSetWork {
  public:
    PerSetDraws prepare(ProgramCache& /*programs*/, const core::RenderInput& in,
                        const core::Camera& camera, const Settings& settings,
                        const std::function<void(std::size_t)>& checkRecords,
                        core::Frame& frame) override {
        const auto start = Clock::now();
        auto timed = [&](const char* stage, const auto& work) -> decltype(auto) {
            const auto stageStart = Clock::now();
            decltype(auto) result = work();
            frame.timingsMs[stage] = elapsedMs(stageStart);
            return result;
        };
        const core::ParticleSet& ps = timed(
            "particle_normals", [&]() -> auto& { return mNormals.particles(in.particles); });
        bool built = !mNormals.reused();
        std::span<const float> radii = timed(
            "radius", [&]() -> auto& { return mRadii.radii(ps, settings.particles); });
        built |= !mRadii.reused();
        // Small droplets, one ellipsoid each: their members' spheres are replaced.
        const Droplets* droplets = nullptr;
        if (mayHaveDroplets(settings.particles)) {
            droplets = &timed(
                "droplets", [&]() -> auto& {
                    return mDroplets.droplets(ps, radii, settings.particles.surfaceLevel,
                                              settings.particles.dropletAtoms);
                });
            built |= !mDroplets.reused();
            if (droplets->firsts.empty()) droplets = nullptr;
        }
        frame.counters["droplets"] = droplets ? static_cast<double>(droplets->firsts.size()) : 0.0;
        if (droplets) radii = droplets->radii;
        const bool anisotropic = settings.particles.shape == ParticleShape::Ellipsoid;
        // Spheres keep the sphere programs; the droplets are drawn apart, first in the buffers.
        const bool dropletsApart = droplets && !anisotropic;
        const std::vector<Ellipsoid>* ellipsoids = nullptr;
        std::vector<Ellipsoid> anisotropicWithDroplets;
        if (anisotropic) {
            ellipsoids = &timed(
                "anisotropy", [&]() -> auto& {
                    return mAnisotropy.ellipsoids(ps, radii, settings.particles.anisotropy);
                });
            built |= !mAnisotropy.reused();
            if (droplets) {
                anisotropicWithDroplets = *ellipsoids;
                for (std::uint32_t first : droplets->firsts)
                    anisotropicWithDroplets[first] = droplets->ellipsoids[first];
                ellipsoids = &anisotropicWithDroplets;
            }
        }
        // realtime.particles.body_sphere_pixels: the bodies small on screen drawn as one sphere.
        BodySphereChoice bodySpheres;
        if (settings.particles.bodySpherePixels > 0.0)
            bodySpheres = chooseBodySpheres(
                mBodySpheres.get(
                    ps,
                    [&] {
                        return core::bodySpheres(in.particles, settings.particles.surfaceLevel);
                    },
                    settings.particles.surfaceLevel, std::span<const glm::vec3>(ps.glow)),
                in.particles.bodies.size(), camera, settings.particles.bodySpherePixels);
        // The culling test is exact for spheres only: an ellipsoid inside the union of its
        // neighbours' bounding spheres may still show between their ellipsoids. Droplets are
        // culled as nothing and drawn whatever the spheres hide.
        std::span<const float> cullRadii = droplets ? droplets->cullRadii : radii;
        std::span<const std::uint32_t> culled;
        if (settings.particles.cullHidden && !anisotropic && !bodySpheres.touchesOthers &&
            cullingIsExact(ps, camera, cullRadii)) {
            culled = timed(
                "cull", [&]() -> auto& { return mCuller.unoccluded(ps, cullRadii); });
            built |= !mCuller.reused();
        }
        bool nothingDrawn = false;
        std::vector<std::uint32_t> drawn = withSurface(culled, cullRadii, nothingDrawn);
        std::vector<std::uint32_t> dropletFirsts;
        if (droplets) dropletFirsts = droplets->firsts;
        if (!bodySpheres.drawn.empty()) {
            if (!nothingDrawn) drawn = withoutReplaced(drawn, ps.body, bodySpheres.replaced);
            nothingDrawn = drawn.empty();
            if (droplets) {
                dropletFirsts = withoutReplaced(dropletFirsts, ps.body, bodySpheres.replaced);
                frame.counters["droplets"] = static_cast<double>(dropletFirsts.size());
            }
        }
        if (droplets) {
            // cullRadii holds zeros, so `drawn` lists the spheres drawn explicitly: the droplets
            // go first (apart) or in index order (every particle an ellipsoid).
            std::vector<std::uint32_t> all;
            if (dropletsApart) {
                all = dropletFirsts;
                all.insert(all.end(), drawn.begin(), drawn.end());
            } else {
                std::merge(drawn.begin(), drawn.end(), dropletFirsts.begin(), dropletFirsts.end(),
                           std::back_inserter(all));
            }
            drawn = std::move(all);
            nothingDrawn = drawn.empty();
        }
        frame.counters["particles_drawn"] =
            nothingDrawn ? 0.0 : static_cast<double>(drawn.empty() ? ps.size() : drawn.size());
        std::span<const FieldNormal> fieldNormalModels;
        std::vector<FieldNormal> withDropletNormals;
        if (settings.particles.normal == NormalModel::Field) {
            fieldNormalModels = timed(
                "field_normals", [&]() -> auto& {
                    return mFieldNormals.normals(ps, radii, drawn);
                });
            built |= !mFieldNormals.reused();
            if (droplets) {
                // A droplet's normal is its ellipsoid's, not a model about its first particle.
                withDropletNormals.assign(fieldNormalModels.begin(), fieldNormalModels.end());
                for (std::size_t k = 0; k < drawn.size(); ++k)
                    if (std::binary_search(dropletFirsts.begin(), dropletFirsts.end(), drawn[k]))
                        withDropletNormals[k] = dropletNormalModel(droplets->ellipsoids[drawn[k]]);
                fieldNormalModels = withDropletNormals;
            }
        }
        const std::vector<GpuParticle> gpuParticles =
            nothingDrawn
                ? std::vector<GpuParticle>{}
                : packParticles(ps, in.scene.camera.position, radii, drawn, fieldNormalModels);
        checkRecords(gpuParticles.size());
        PerSetDraws out;
        mParticles = gl::Buffer::of(std::span<const GpuParticle>(gpuParticles));
        out.particles = &mParticles;
        out.draw.count = gpuParticles.size();
        if (dropletsApart) {
            const std::size_t count = dropletFirsts.size();
            const std::vector<GpuEllipsoid> packed =
                packEllipsoids(droplets->ellipsoids, dropletFirsts);
            mEllipsoids = gl::Buffer::of(std::span<const GpuEllipsoid>(packed));
            out.droplets = SceneBuffers::Droplets{&mEllipsoids, {count}};
            out.draw = {gpuParticles.size() - count, nullptr, 0, count};
        } else if (ellipsoids) {
            const std::vector<GpuEllipsoid> packed =
                nothingDrawn ? std::vector<GpuEllipsoid>{} : packEllipsoids(*ellipsoids, drawn);
            mEllipsoids = gl::Buffer::of(std::span<const GpuEllipsoid>(packed));
            out.ellipsoids = &mEllipsoids;
        }
        frame.counters["body_spheres"] = static_cast<double>(bodySpheres.drawn.size());
        if (!bodySpheres.drawn.empty()) {
            const std::vector<GpuParticle> packed =
                packBodySpheres(bodySpheres.drawn, in.particles.bodies, in.scene.camera.position);
            mBodySphereRecords = gl::Buffer::of(std::span<const GpuParticle>(packed));
            out.bodySpheres = SceneBuffers::BodySpheres{&mBodySphereRecords, {packed.size()}};
        }
        if (usesKernels(settings)) {
            const std::vector<std::uint32_t>& surfaceKernels = timed(
                "kernels", [&]() -> auto& {
                    return mSurfaceKernels.kernels(ps, settings.particles.surfaceLevel);
                });
            built |= !mSurfaceKernels.reused();
            // A body sphere keeps its own normal: its body's kernels are not splatted.
            std::vector<std::uint32_t> withoutSpheres;
            if (!bodySpheres.drawn.empty() && !surfaceKernels.empty())
                withoutSpheres = withoutReplaced(surfaceKernels, ps.body, bodySpheres.replaced);
            const std::vector<std::uint32_t>& reaching =
                bodySpheres.drawn.empty() ? surfaceKernels : withoutSpheres;
            frame.counters["kernels_splatted"] = static_cast<double>(reaching.size());
            if (!reaching.empty()) {
                const std::vector<GpuKernel> packed =
                    packKernels(ps, in.scene.camera.position, reaching);
                mKernels = gl::Buffer::of(std::span<const GpuKernel>(packed));
                out.kernels = &mKernels;
                out.kernelDraw.count = packed.size();
            }
        }
        frame.counters["per_set_builds"] = built ? 1.0 : 0.0;
        gl::checkErrors("upload");
        gl::finish();
        double perSet = 0.0;
        for (const std::string& stage : perSetStages()) perSet += frame.timingsMs[stage];
        frame.timingsMs["upload"] = elapsedMs(start) - perSet;
        return out;
    }

  private:
    DerivedNormalsCache mNormals;        // the particle normals, where a set comes without them
    ImpostorRadiusCache mRadii;          // the impostor radii
    DropletCache mDroplets;              // the small droplets' ellipsoids
    AnisotropyCache mAnisotropy;         // the ellipsoids (shape = "ellipsoid")
    OcclusionCuller mCuller;             // the culling (view-independent)
    FieldNormalCache mFieldNormals;      // the G-buffer's field normal models
    SurfaceKernelCache mSurfaceKernels;  // the kernels the gradient pass adds
    // The bodies' level-set spheres (particles.body_sphere_pixels), and their inputs: the surface
    // level and the glow they average.
    SetCache<std::vector<core::BodySphere>, double, std::span<const glm::vec3>> mBodySpheres;
    gl::Buffer mParticles, mEllipsoids, mKernels, mBodySphereRecords;  // the frame's records
};

}  // namespace

std::unique_ptr<PerSetWork> makeCpuPerSetWork() {
    return std::make_unique<CpuPerSetWork>();
}

}  // namespace twinrender::realtime
