#include "realtime/renderer.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "core/cancellation.h"
#include "core/derived_attributes.h"
#include "core/error.h"
#include "realtime/anisotropy.h"
#include "realtime/droplets.h"
#include "realtime/field_normal.h"
#include "realtime/frame_assembly.h"
#include "realtime/gl/context.h"
#include "realtime/gl/error.h"
#include "realtime/gl/pipeline.h"
#include "realtime/gl/readback.h"
#include "realtime/gl/timer_query.h"
#include "realtime/gpu_scene.h"
#include "realtime/impostor_radius.h"
#include "realtime/light_frustum.h"
#include "realtime/occlusion_culling.h"
#include "realtime/passes.h"
#include "realtime/per_set_gpu.h"
#include "realtime/program_variants.h"
#include "realtime/surface_kernels.h"

namespace twinrender::realtime {

// per_set = "cpu": a set that came without normals (core::buildParticles leaves them to the
// real-time renderer), copied with core::deriveNormals' normals and kept for the set.
class DerivedNormalsCache {
  public:
    const core::ParticleSet& particles(const core::SceneParticles& in) {
        mGiven = in.hasNormals;
        if (mGiven) return in.particles;
        return mCache.get(in.particles, [&] {
            core::ParticleSet out = in.particles;
            core::deriveNormals(out, in.bodies);
            return out;
        });
    }
    bool reused() const { return mGiven || mCache.reused(); }

  private:
    bool mGiven = false;
    SetCache<core::ParticleSet> mCache;
};

struct DeviceState {
    explicit DeviceState(const gl::Context& c) : context(c) {}
    const gl::Context& context;
    gl::Limits limits;
    ProgramCache programs;
    DerivedNormalsCache normals;        // the particle normals, where a set comes without them
    OcclusionCuller culler;             // keeps the last particle set's answer (view-independent)
    FieldNormalCache fieldNormals;      // the same for the G-buffer's field normal models
    ImpostorRadiusCache radii;          // and for the impostor radii
    SurfaceKernelCache surfaceKernels;  // and for the kernels the gradient pass adds
    AnisotropyCache anisotropy;         // and for the ellipsoids (shape = "ellipsoid")
    DropletCache droplets;              // and for the small droplets' ellipsoids
    GpuPerSet perSetGpu;                // per_set = "gpu": all of the above on the GPU
    // The read-back's pixel buffers, kept between frames.
    gl::TextureReadback readback;
    // Images handed back by Renderer::recycle, reused when the size and channels match.
    core::Image spareImage, spareDisplay;
};

Device::Device(const gl::Context& context) : mState(std::make_unique<DeviceState>(context)) {
    context.makeCurrent();
    mState->limits = gl::queryLimits();
}

Device::~Device() = default;

std::vector<std::string> Device::programNames() const {
    return mState->programs.names();
}

namespace {

using Clock = std::chrono::steady_clock;

// The stages of the work done once per particle set (timings_ms; 0 when they do not run or
// an unchanged set reuses them). "upload" and, with per_set = "gpu", "pack" are per frame.
constexpr const char* PER_SET_STAGES[] = {"grid",    "particle_normals", "radius",     "droplets",
                                          "kernels", "field_normals",    "anisotropy", "cull"};

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

FrameUniforms makeUniforms(const core::Scene& scene, const core::Camera& camera,
                           const core::SceneParticles& particles, const Settings& settings,
                           const LightFrustum& light) {
    const core::CameraSettings& cs = scene.camera;
    FrameUniforms u;
    glm::dmat4 view = camera.viewMatrix();
    view[3] = glm::dvec4(0.0, 0.0, 0.0, 1.0);  // positions are camera-relative: rotation only
    u.viewFromWorld = glm::mat4(view);
    const double fovY = glm::radians(cs.fovYDeg);
    // Reversed-Z: the [0, 1] clip range with near and far swapped maps near -> 1, far -> 0.
    u.clipFromView = settings.depth == DepthMode::Reversed
                         ? glm::mat4(glm::perspectiveRH_ZO(fovY, camera.aspect(), cs.far, cs.near))
                         : glm::mat4(glm::perspectiveRH_NO(fovY, camera.aspect(), cs.near, cs.far));
    u.lightView = glm::mat4(light.view);
    u.lightClip = glm::mat4(light.clip);
    u.viewport = glm::vec4(cs.width, cs.height, 1.0 / cs.width, 1.0 / cs.height);
    u.camera = glm::vec4(cs.near, cs.far, camera.tanHalfFovY(), std::log2(1.0 + cs.far / cs.near));
    u.light = glm::vec4(glm::vec3(glm::normalize(scene.light.direction)), scene.light.intensity);
    u.lightColor = glm::vec4(glm::vec3(scene.light.color), scene.light.ambient);
    u.shadowRange =
        glm::vec4(light.nearDepth, light.farDepth, light.texelSize, settings.shadowMap.resolution);
    u.shadowBias = glm::vec4(settings.shadowMap.bias, settings.shadowMap.slopeBias,
                             settings.shadowMap.pcfRadius,
                             std::tan(glm::radians(scene.light.angularRadiusDeg)));
    // The share of the impostor's own normal in the G-buffer's (gbuffer.frag).
    const double impostorNormal = settings.particles.normal == NormalModel::Blend
                                      ? settings.particles.sphereNormalWeight
                                  : settings.particles.normal == NormalModel::Sphere ? 1.0
                                                                                     : 0.0;
    u.misc = glm::vec4(cs.exposure, settings.particles.radiusScale, impostorNormal, 0.0);
    (void)particles;
    return u;
}

// Occlusion culling assumes that every ray starts outside all spheres. Rays start at the near
// plane; every point of the frustum in front of it lies within nearReach of the eye, so no
// sphere reaching into that ball means the near plane cannot cut a body open.
double nearReach(const core::Camera& camera) {
    const double t = camera.tanHalfFovY();
    return camera.settings().near *
           std::sqrt(1.0 + t * t * (1.0 + camera.aspect() * camera.aspect()));
}

bool cullingIsExact(const core::ParticleSet& ps, const core::Camera& camera,
                    std::span<const float> radii) {
    const double reach = nearReach(camera);
    for (std::size_t i = 0; i < ps.size(); ++i)
        if (glm::length(glm::dvec3(ps.position[i]) - camera.position()) - radii[i] <= reach)
            return false;
    return true;
}

bool sceneEmits(const core::ParticleSet& ps, const std::vector<core::Material>& materials) {
    for (const auto& m : materials)
        for (float v : m.emission.image().pixels())
            if (v != 0.0f) return true;
    for (const glm::vec3& g : ps.glow)
        if (g != glm::vec3(0.0f)) return true;
    return false;
}

// ---- Check limits ----

// Throws core::InputError when the image or the shadow map is larger than the device allows,
// or a particle names a material the scene does not have.
void checkLimits(const core::RenderInput& in, const Settings& settings, const DeviceState& d) {
    const std::string file = in.scene.file.string();
    const int w = in.scene.camera.width, h = in.scene.camera.height;
    const gl::Limits& limits = d.limits;
    if (w > limits.maxTextureSize || h > limits.maxTextureSize || w > limits.maxViewportWidth ||
        h > limits.maxViewportHeight)
        throw core::InputError(fmt::format(
            "{}: the image of {}x{} pixels exceeds the GL device's limit of {}x{} ({}); lower "
            "camera.width / camera.height",
            file, w, h, std::min(limits.maxTextureSize, limits.maxViewportWidth),
            std::min(limits.maxTextureSize, limits.maxViewportHeight), d.context.renderer()));
    if (usesShadowMap(settings.shadows) && settings.shadowMap.resolution > limits.maxTextureSize)
        throw core::InputError(fmt::format(
            "{}: realtime.shadow_map.resolution = {} exceeds the GL device's texture limit {} ({})",
            file, settings.shadowMap.resolution, limits.maxTextureSize, d.context.renderer()));
    const core::ParticleSet& ps = in.particles.particles;
    for (std::size_t i = 0; i < ps.size(); ++i)
        if (ps.material[i] >= in.materials.size())
            throw core::InputError(
                fmt::format("{}: particle {} has material {} but the scene has {}", file, i,
                            ps.material[i], in.materials.size()));
}

// ---- Compile ----

// Compiles (once per device) every program a frame with these settings builds
// (program_variants.h), so that none is compiled inside a frame.
void compilePrograms(ProgramCache& programs, const Settings& settings, bool emits) {
    for (const ProgramVariant& v : programVariants(settings, emits)) {
        if (v.userShader)
            userSurfaceProgram(programs, settings.surface);  // its errors are bad input
        else
            v.build(programs);
    }
    if (settings.perSet == PerSetDevice::Gpu)
        compilePerSetPrograms(programs, perSetRequest(settings));  // and the stage clock
    gl::finish();
}

// ---- Upload ----

// Throws core::InputError when the packed particles, the per-set work's grid (read as buffer
// textures on the GPU path: per_set_gpu.h) or the material texels exceed the device's buffer
// limits.
void checkBufferLimits(const core::RenderInput& in, const DeviceState& d, std::size_t particles,
                       std::size_t texels, PerSetDevice perSet) {
    const gl::Limits& limits = d.limits;
    const std::size_t bytes = particles * sizeof(GpuParticle);
    if (static_cast<long long>(bytes) > limits.maxStorageBlockBytes)
        throw core::InputError(fmt::format(
            "{}: {} particles take {} MB, over the GL device's storage-buffer limit of {} MB ({})",
            in.scene.file.string(), particles, bytes >> 20, limits.maxStorageBlockBytes >> 20,
            d.context.renderer()));
    const std::size_t gridTexels = perSetTexels(in.particles.particles.size());
    if (perSet == PerSetDevice::Gpu &&
        static_cast<long long>(gridTexels) > limits.maxTextureBufferTexels)
        throw core::InputError(
            fmt::format("{}: {} particles need a neighbour grid of {} texels, over the GL device's "
                        "buffer-texture limit of {} ({}); set realtime.per_set = \"cpu\"",
                        in.scene.file.string(), in.particles.particles.size(), gridTexels,
                        limits.maxTextureBufferTexels, d.context.renderer()));
    if (static_cast<long long>(texels) > limits.maxTextureBufferTexels)
        throw core::InputError(fmt::format(
            "{}: the material textures hold {} texels, over the GL device's buffer-texture limit "
            "of {} ({}); use smaller texture images",
            in.scene.file.string(), texels, limits.maxTextureBufferTexels, d.context.renderer()));
}

// What upload() puts on the device: the scene's buffers, and the particles' kernels when the
// normals come from the colour field's gradient (the CPU path's own buffers, or the GPU path's).
struct Uploaded {
    SceneBuffers scene;
    std::unique_ptr<gl::Buffer> particles, ellipsoids, kernels;  // per_set = "cpu"
    const gl::Buffer* kernelBuffer = nullptr;  // those that reach the surface (surface_kernels.h)
    DrawList kernelDraw;
};

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

// The frame uniforms and the materials, uploaded; the particle buffers are left to the caller.
SceneBuffers sceneBuffers(DeviceState& d, const core::RenderInput& in, const core::Camera& camera,
                          const Settings& settings, std::size_t particles) {
    const LightFrustum light =
        fitLightFrustum(in.particles.boundsMin, in.particles.boundsMax, in.scene.camera.position,
                        in.scene.light.direction, settings.shadowMap.resolution);
    const FrameUniforms uniforms = makeUniforms(in.scene, camera, in.particles, settings, light);
    const GpuMaterials gpuMaterials = packMaterials(in.materials);
    checkBufferLimits(in, d, particles, gpuMaterials.texels.size() / 3, settings.perSet);
    return {gl::Buffer::of(std::span<const FrameUniforms>(&uniforms, 1)),
            nullptr,
            gl::BufferTexture::of(std::span<const float>(gpuMaterials.texels),
                                  gl::BufferFormat::RGB32F),
            gl::Buffer::of(std::span<const GpuMaterial>(gpuMaterials.records)),
            {},
            nullptr,
            std::nullopt};
}

// per_set = "cpu": the particles that may be seen (hidden ones culled where that is exact,
// those without a surface left out) with their impostor radii, ellipsoids and field normal
// models, packed on the CPU and uploaded with the materials and the frame uniforms. Times
// "radius", "kernels", "anisotropy", "field_normals" and "cull" (kept per particle set by the
// device) and "upload" (the rest), counts "particles_drawn" and "per_set_builds".
Uploaded uploadCpu(DeviceState& d, const core::RenderInput& in, const core::Camera& camera,
                   const Settings& settings, core::Frame& frame) {
    const auto start = Clock::now();
    auto timed = [&](const char* stage, const auto& work) -> decltype(auto) {
        const auto stageStart = Clock::now();
        decltype(auto) result = work();
        frame.timingsMs[stage] = msSince(stageStart);
        return result;
    };
    const core::ParticleSet& ps = timed(
        "particle_normals", [&]() -> auto& { return d.normals.particles(in.particles); });
    bool built = !d.normals.reused();
    std::span<const float> radii = timed(
        "radius", [&]() -> auto& { return d.radii.radii(ps, settings.particles); });
    built |= !d.radii.reused();
    // Small droplets, one ellipsoid each: their members' spheres are replaced.
    const Droplets* droplets = nullptr;
    if (mayHaveDroplets(settings.particles)) {
        droplets = &timed(
            "droplets", [&]() -> auto& {
                return d.droplets.droplets(ps, radii, settings.particles.surfaceLevel,
                                           settings.particles.dropletAtoms);
            });
        built |= !d.droplets.reused();
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
                return d.anisotropy.ellipsoids(ps, radii, settings.particles.anisotropy);
            });
        built |= !d.anisotropy.reused();
        if (droplets) {
            anisotropicWithDroplets = *ellipsoids;
            for (std::uint32_t first : droplets->firsts)
                anisotropicWithDroplets[first] = droplets->ellipsoids[first];
            ellipsoids = &anisotropicWithDroplets;
        }
    }
    // The culling test is exact for spheres only: an ellipsoid inside the union of its
    // neighbours' bounding spheres may still show between their ellipsoids. Droplets are
    // culled as nothing and drawn whatever the spheres hide.
    std::span<const float> cullRadii = droplets ? droplets->cullRadii : radii;
    std::span<const std::uint32_t> culled;
    if (settings.particles.cullHidden && !anisotropic && cullingIsExact(ps, camera, cullRadii)) {
        culled = timed(
            "cull", [&]() -> auto& { return d.culler.unoccluded(ps, cullRadii); });
        built |= !d.culler.reused();
    }
    bool nothingDrawn = false;
    std::vector<std::uint32_t> drawn = withSurface(culled, cullRadii, nothingDrawn);
    if (droplets) {
        // cullRadii holds zeros, so `drawn` lists the spheres drawn explicitly: the droplets
        // go first (apart) or in index order (every particle an ellipsoid).
        std::vector<std::uint32_t> all;
        if (dropletsApart) {
            all = droplets->firsts;
            all.insert(all.end(), drawn.begin(), drawn.end());
        } else {
            std::merge(drawn.begin(), drawn.end(), droplets->firsts.begin(), droplets->firsts.end(),
                       std::back_inserter(all));
        }
        drawn = std::move(all);
        nothingDrawn = false;
    }
    frame.counters["particles_drawn"] =
        nothingDrawn ? 0.0 : static_cast<double>(drawn.empty() ? ps.size() : drawn.size());
    std::span<const FieldNormal> fieldNormalModels;
    std::vector<FieldNormal> withDropletNormals;
    if (settings.particles.normal == NormalModel::Field) {
        fieldNormalModels = timed(
            "field_normals", [&]() -> auto& { return d.fieldNormals.normals(ps, radii, drawn); });
        built |= !d.fieldNormals.reused();
        if (droplets) {
            // A droplet's normal is its ellipsoid's, not a model about its first particle.
            withDropletNormals.assign(fieldNormalModels.begin(), fieldNormalModels.end());
            for (std::size_t k = 0; k < drawn.size(); ++k)
                if (std::binary_search(droplets->firsts.begin(), droplets->firsts.end(), drawn[k]))
                    withDropletNormals[k] = dropletNormalModel(droplets->ellipsoids[drawn[k]]);
            fieldNormalModels = withDropletNormals;
        }
    }
    const std::vector<GpuParticle> gpuParticles =
        nothingDrawn ? std::vector<GpuParticle>{}
                     : packParticles(ps, in.scene.camera.position, radii, drawn, fieldNormalModels);
    Uploaded out{
        sceneBuffers(d, in, camera, settings, gpuParticles.size()), {}, {}, {}, nullptr, {}};
    out.particles =
        std::make_unique<gl::Buffer>(gl::Buffer::of(std::span<const GpuParticle>(gpuParticles)));
    out.scene.particles = out.particles.get();
    out.scene.draw.count = gpuParticles.size();
    if (dropletsApart) {
        const std::size_t count = droplets->firsts.size();
        const std::vector<GpuEllipsoid> packed =
            packEllipsoids(droplets->ellipsoids, droplets->firsts);
        out.ellipsoids =
            std::make_unique<gl::Buffer>(gl::Buffer::of(std::span<const GpuEllipsoid>(packed)));
        out.scene.droplets = SceneBuffers::Droplets{out.ellipsoids.get(), {count}};
        out.scene.draw = {gpuParticles.size() - count, nullptr, 0, count};
    } else if (ellipsoids) {
        const std::vector<GpuEllipsoid> packed =
            nothingDrawn ? std::vector<GpuEllipsoid>{} : packEllipsoids(*ellipsoids, drawn);
        out.ellipsoids =
            std::make_unique<gl::Buffer>(gl::Buffer::of(std::span<const GpuEllipsoid>(packed)));
        out.scene.ellipsoids = out.ellipsoids.get();
    }
    if (usesKernels(settings)) {
        const std::vector<std::uint32_t>& reaching = timed(
            "kernels", [&]() -> auto& {
                return d.surfaceKernels.kernels(ps, settings.particles.surfaceLevel);
            });
        built |= !d.surfaceKernels.reused();
        frame.counters["kernels_splatted"] = static_cast<double>(reaching.size());
        if (!reaching.empty()) {
            const std::vector<GpuKernel> packed =
                packKernels(ps, in.scene.camera.position, reaching);
            out.kernels =
                std::make_unique<gl::Buffer>(gl::Buffer::of(std::span<const GpuKernel>(packed)));
            out.kernelBuffer = out.kernels.get();
            out.kernelDraw.count = packed.size();
        }
    }
    frame.counters["per_set_builds"] = built ? 1.0 : 0.0;
    gl::checkErrors("upload");
    gl::finish();
    double perSet = 0.0;
    for (const char* stage : PER_SET_STAGES) perSet += frame.timingsMs[stage];
    frame.timingsMs["upload"] = msSince(start) - perSet;
    return out;
}

// per_set = "gpu" (per_set_gpu.h): the particles' attributes uploaded once per set, the per-set
// answers computed and the draw lists packed by compute passes; the draws take their counts
// from indirect commands. Times "upload" (wall clock) and the GPU stages (timer queries, read
// after the frame by readGpuTimings), counts "per_set_builds".
Uploaded uploadGpu(DeviceState& d, const core::RenderInput& in, const core::Camera& camera,
                   const Settings& settings, core::Frame& frame) {
    const core::ParticleSet& ps = in.particles.particles;
    Uploaded out{sceneBuffers(d, in, camera, settings, ps.size()), {}, {}, {}, nullptr, {}};
    const PerSetRequest request = perSetRequest(settings);
    GpuPerSet& g = d.perSetGpu;
    const bool built =
        g.update(d.programs, ps, request,
                 in.particles.hasNormals ? std::span<const core::BodyInfo>() : in.particles.bodies);
    frame.counters["per_set_builds"] = built ? 1.0 : 0.0;
    frame.timingsMs["upload"] = g.uploadMs();
    g.pack(d.programs, {in.scene.camera.position, nearReach(camera)});
    gl::checkErrors("per-set compute passes");
    if (ps.size() == 0) {
        out.particles = std::make_unique<gl::Buffer>(gl::Buffer::zeros(16));
        out.scene.particles = out.particles.get();
        return out;
    }
    out.scene.particles = &g.particles();
    out.scene.draw = {0, &g.drawCommands(), GpuPerSet::particleDrawOffset()};
    if (g.ellipsoidsDrawn()) out.scene.ellipsoids = &g.ellipsoids();
    if (g.dropletsApart())
        out.scene.droplets = SceneBuffers::Droplets{
            &g.dropletEllipsoids(), {0, &g.drawCommands(), GpuPerSet::dropletDrawOffset()}};
    return out;
}

Uploaded upload(DeviceState& d, const core::RenderInput& in, const core::Camera& camera,
                const Settings& settings, core::Frame& frame) {
    return settings.perSet == PerSetDevice::Gpu ? uploadGpu(d, in, camera, settings, frame)
                                                : uploadCpu(d, in, camera, settings, frame);
}

// per_set = "gpu": the compute stages' GPU times and the draw counts, once the frame is done.
void readGpuPerSet(DeviceState& d, const Settings& settings, core::Frame& frame) {
    if (settings.perSet != PerSetDevice::Gpu) return;
    for (const auto& [stage, ms] : d.perSetGpu.takeTimings()) frame.timingsMs[stage] = ms;
    d.perSetGpu.afterFrame();
    frame.counters["particles_drawn"] = d.perSetGpu.drawnCount();
    frame.counters["droplets"] = d.perSetGpu.dropletCount();
    // normal = "gradient": the gradient is gathered through the grid, no kernel is splatted.
}

// ---- Passes ----

// What the passes read besides each other's targets.
struct PassInputs {
    ProgramCache& programs;
    const SceneBuffers& scene;
    const Settings& settings;
    const gl::Buffer* kernels = nullptr;  // normal = "gradient": the kernels that reach the surface
    DrawList kernelDraw;
    int width = 0, height = 0;
    bool emits = false;  // whether anything emits: else the emission buffer is zero
    float exposure = 1.0f;
    std::vector<OcclusionSphere> spheres = {};  // shadows = "spheres": camera-relative
    // normal = "gradient" with per_set = "gpu": the grid the gradient is gathered through
    // instead, and the camera's world position.
    GpuPerSet* gradientGrid = nullptr;
    glm::dvec3 camera{0.0};
};

// The textures the passes write, each pass reading those of the passes before it, and the
// timer query of each pass that ran.
struct PassTargets {
    std::optional<gl::Texture> shadowMap;
    std::optional<GBuffer> gbuffer;
    std::optional<gl::Texture> gradientNormalUv;  // normal = "gradient"
    std::optional<SmoothedSurface> smoothed;
    std::optional<FilteredSurface> filtered;
    std::optional<gl::Texture> beauty;   // linear beauty, light visibility
    std::optional<gl::Texture> display;  // bloom and tonemap
    std::vector<std::pair<const char*, gl::TimerQuery>> timers;

    // The surface before smoothing: the G-buffer's, with the gradient pass's normals when it
    // ran.
    const gl::Texture& surfaceNormalUv() const {
        return gradientNormalUv ? *gradientNormalUv : gbuffer->normalUv;
    }
    // The surface the shade pass reads: smoothed when SSSS ran, filtered when a depth filter
    // or the user's shader did.
    const gl::Texture& normalUv() const {
        return smoothed   ? smoothed->resultNormalUv()
               : filtered ? filtered->normalUv
                          : surfaceNormalUv();
    }
    const gl::Texture& emission() const {
        return smoothed   ? smoothed->resultEmission(*gbuffer)
               : filtered ? filtered->resultEmission(*gbuffer)
                          : gbuffer->emission;
    }
    const gl::Texture& surface() const {
        return filtered ? filtered->resultSurface(*gbuffer) : gbuffer->surface;
    }
};

ShadeInputs shadeInputs(const PassInputs& in, const PassTargets& t) {
    ShadeInputs s;
    s.normalUv = &t.normalUv();
    s.emissionBuffer = &t.emission();
    s.emission = in.emits;
    s.surface = &t.surface();
    s.depth = &t.gbuffer->depth;
    s.depthMode = in.settings.depth;
    s.shadowMap = t.shadowMap ? &*t.shadowMap : nullptr;
    s.shadows = in.settings.shadows;
    s.shadowSettings = in.settings.shadowMap;
    s.spheres = in.spheres;
    return s;
}

// One pass of the frame: its timings_ms key, whether the settings need it, and what it does.
struct Pass {
    const char* name;
    bool (*runs)(const PassInputs&);
    void (*run)(const PassInputs&, PassTargets&);
};

bool always(const PassInputs&) {
    return true;
}

// The frame's passes, in order (passes.h). A pass that does not run reports 0 ms; a new pass is
// a new row (and, if later passes read its output, a target).
const Pass PASSES[] = {
    {"shadow", [](const PassInputs& in) { return usesShadowMap(in.settings.shadows); },
     [](const PassInputs& in, PassTargets& t) {
         t.shadowMap.emplace(
             runShadowPass(in.programs, in.scene, in.settings.shadows, in.settings.shadowMap));
     }},
    {"gbuffer", always,
     [](const PassInputs& in, PassTargets& t) {
         t.gbuffer.emplace(
             runGBufferPass(in.programs, in.scene, in.width, in.height, in.settings.depth));
     }},
    // Not under a depth filter, whose normals are rebuilt from the filtered depth (upload
    // leaves the kernels out then).
    {"normals",
     [](const PassInputs& in) {
         return in.gradientGrid != nullptr ||
                (in.kernels != nullptr && (in.kernelDraw.commands || in.kernelDraw.count > 0));
     },
     [](const PassInputs& in, PassTargets& t) {
         if (in.gradientGrid)
             t.gradientNormalUv.emplace(runGradientGatherPass(in.programs, in.scene,
                                                              *in.gradientGrid, in.camera,
                                                              *t.gbuffer, in.settings.depth));
         else
             t.gradientNormalUv.emplace(runGradientNormalPass(
                 in.programs, in.scene, *in.kernels, in.kernelDraw, *t.gbuffer, in.settings.depth));
     }},
    {"ssss", [](const PassInputs& in) { return usesSsss(in.settings); },
     [](const PassInputs& in, PassTargets& t) {
         t.smoothed.emplace(runSsssPass(in.programs, *t.gbuffer, t.surfaceNormalUv(),
                                        in.settings.ssss, in.emits, in.settings.depth));
     }},
    {"surface", [](const PassInputs& in) { return usesSurfaceFilter(in.settings); },
     [](const PassInputs& in, PassTargets& t) {
         t.filtered.emplace(
             runSurfacePass(in.programs, *t.gbuffer, t.surfaceNormalUv(), in.settings.surface));
     }},
    {"shade", always,
     [](const PassInputs& in, PassTargets& t) {
         t.beauty.emplace(runShadePass(in.programs, shadeInputs(in, t)));
     }},
    {"post", always,
     [](const PassInputs& in, PassTargets& t) {
         t.display.emplace(runPostPass(in.programs, *t.beauty, in.settings.bloom, in.exposure));
     }},
};

// llvmpipe answers the first timer query around rendering with a timestamp instead of an
// elapsed time; a query around a tiny clear absorbs that.
void warmUpTimerQueries() {
    gl::Texture texture(1, 1, gl::Format::R32F);
    gl::Framebuffer framebuffer("timer warm-up", {{&texture}});
    gl::TimerQuery warmUp;
    warmUp.begin();
    framebuffer.bind();
    framebuffer.clearColor(0, glm::vec4(0.0f));
    warmUp.end();
    warmUp.milliseconds();
}

// The passes the settings need, each inside a GL timer query (read after the read-back, which
// waits for the passes anyway).
PassTargets runPasses(const PassInputs& in) {
    warmUpTimerQueries();
    PassTargets t;
    for (const Pass& pass : PASSES) {
        if (!pass.runs(in)) continue;
        t.timers.emplace_back(pass.name, gl::TimerQuery());
        t.timers.back().second.begin();
        pass.run(in, t);
        t.timers.back().second.end();
        gl::checkErrors(pass.name);
    }
    return t;
}

// ---- Read back ----

// Reads an RGBA32F texture, bottom row first, into `out` (resized; kept by the device between
// frames, so that its pages are not faulted in again every frame).
// `spare` when it has the size and channels asked for (its values are stale), else a new
// image of zeros.
core::Image reuseOrCreate(core::Image& spare, int w, int h, std::vector<std::string> channels) {
    if (spare.width() == w && spare.height() == h && spare.channelNames() == channels)
        return std::move(spare);
    return core::Image(w, h, std::move(channels));
}

// Reads back what the shade pass read, the beauty and the display, and assembles the frame's
// AOV and display images (frame_assembly.h). Times "readback".
void readBack(DeviceState& d, const PassTargets& t, bool emits, int w, int h, core::Frame& frame) {
    const auto start = Clock::now();
    // Every read queued, then one wait (gl/readback.h).
    enum Slot : std::size_t { NORMAL_UV, EMISSION, SURFACE, BEAUTY_SHADOW, DISPLAY };
    gl::TextureReadback& r = d.readback;
    r.read(NORMAL_UV, t.normalUv());
    // Without emitters the emission buffer is zero, as the image's channels already are.
    if (emits) r.read(EMISSION, t.emission());
    r.read(SURFACE, t.surface());
    r.read(BEAUTY_SHADOW, *t.beauty);
    r.read(DISPLAY, *t.display);
    r.wait();
    frame.image = reuseOrCreate(d.spareImage, w, h, core::aov::channelNames());
    frame.display = reuseOrCreate(d.spareDisplay, w, h, {"R", "G", "B"});
    ReadBackBuffers buffers;
    buffers.width = w;
    buffers.height = h;
    buffers.normalUv = r.pixels(NORMAL_UV);
    if (emits) buffers.emission = r.pixels(EMISSION);
    buffers.surface = r.pixels(SURFACE);
    buffers.beautyShadow = r.pixels(BEAUTY_SHADOW);
    buffers.display = r.pixels(DISPLAY);
    assembleFrame(buffers, frame.image, frame.display);
    frame.timingsMs["readback"] = msSince(start);
}

}  // namespace

Renderer::Renderer(Device& device, const Settings& settings)
    : mDevice(*device.mState), mSettings(settings) {
    // A user's shader that does not compile is bad input: said before anything renders.
    if (settings.surface.method == SurfaceMethod::Shader) {
        mDevice.context.makeCurrent();
        userSurfaceProgram(mDevice.programs, settings.surface);
    }
}

void Renderer::recycle(core::Frame&& old) {
    mDevice.spareImage = std::move(old.image);
    mDevice.spareDisplay = std::move(old.display);
}

core::Frame Renderer::render(const core::RenderInput& in) {
    core::throwIfCancelled(in.cancel);
    DeviceState& d = mDevice;
    d.context.makeCurrent();
    checkLimits(in, mSettings, d);
    const core::Camera camera(in.scene.camera);
    core::Frame frame;
    frame.renderer = "realtime";
    frame.device = d.context.renderer();
    frame.settings = toJson(mSettings);
    frame.particleCount = in.particles.particles.size();
    for (const char* stage : PER_SET_STAGES) frame.timingsMs[stage] = 0.0;
    for (const char* stage : {"upload", "pack", "readback"}) frame.timingsMs[stage] = 0.0;
    for (const Pass& pass : PASSES) frame.timingsMs[pass.name] = 0.0;

    // Whether anything emits: otherwise the emission buffer is zero and SSSS leaves it alone.
    const bool emits = sceneEmits(in.particles.particles, in.materials);
    // Compiling programs is set-up, like creating the context: not part of the render time.
    const auto compileStart = Clock::now();
    compilePrograms(d.programs, mSettings, emits);
    frame.timingsMs["compile"] = msSince(compileStart);

    const auto totalStart = Clock::now();
    const Uploaded uploaded = upload(d, in, camera, mSettings, frame);
    PassInputs passInputs{
        d.programs,          uploaded.scene, mSettings,      uploaded.kernelBuffer,
        uploaded.kernelDraw, camera.width(), camera.height()};
    passInputs.emits = emits;
    if (mSettings.perSet == PerSetDevice::Gpu && usesKernels(mSettings) &&
        !in.particles.particles.position.empty()) {
        passInputs.gradientGrid = &d.perSetGpu;
        passInputs.camera = in.scene.camera.position;
    }
    passInputs.exposure = static_cast<float>(in.scene.camera.exposure);
    if (mSettings.shadows == ShadowMode::Spheres) {
        passInputs.spheres = occlusionSpheres(in.particles);
        for (auto& s : passInputs.spheres) s.centre -= in.scene.camera.position;
        frame.counters["occlusion_spheres"] = static_cast<double>(passInputs.spheres.size());
    }
    // The per-particle-set work (radii, anisotropy, culling) can take seconds on a large set.
    core::throwIfCancelled(in.cancel);
    const PassTargets targets = runPasses(passInputs);
    readBack(d, targets, emits, camera.width(), camera.height(), frame);
    readGpuPerSet(d, mSettings, frame);
    for (const auto& [name, query] : targets.timers) frame.timingsMs[name] = query.milliseconds();
    frame.timingsMs["total"] = msSince(totalStart);
    return frame;
}

}  // namespace twinrender::realtime
