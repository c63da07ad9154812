#include "realtime/renderer.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/body_sphere.h"
#include "core/camera.h"
#include "core/cancellation.h"
#include "core/derived_attributes.h"
#include "core/error.h"
#include "realtime/ao_traced.h"
#include "realtime/error_split.h"
#include "realtime/frame_assembly.h"
#include "realtime/frame_graph.h"
#include "realtime/gl/context.h"
#include "realtime/gl/conversions.h"
#include "realtime/gl/error.h"
#include "realtime/gl/pipeline.h"
#include "realtime/gl/readback.h"
#include "realtime/gl/timer_query.h"
#include "realtime/gpu_scene.h"
#include "realtime/light_frustum.h"
#include "realtime/occlusion_culling.h"
#include "realtime/passes.h"
#include "realtime/per_set.h"
#include "realtime/per_set_gpu.h"
#include "realtime/program_variants.h"

namespace twinrender::realtime {

struct DeviceState {
    explicit DeviceState(const gl::Context& c) : context(c) {}
    const gl::Context& context;
    gl::Limits limits;
    ProgramCache programs;
    // The work done once per particle set, each back end keeping its answers (per_set.h).
    std::unique_ptr<PerSetWork> perSetCpu = makeCpuPerSetWork();
    std::unique_ptr<PerSetWork> perSetGpu = makeGpuPerSetWork();
    PerSetWork& perSet(const Settings& settings) const {
        return settings.perSet == PerSetDevice::Gpu ? *perSetGpu : *perSetCpu;
    }
    // The read-back's pixel buffers, kept between frames.
    gl::TextureReadback readback;
    // ao.method = "traced": the spheres it traces, kept per particle set.
    OcclusionGridCache occlusionGrid;
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

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

FrameUniforms makeUniforms(const core::Scene& scene, const core::Camera& camera,
                           const Settings& settings, const LightFrustum& light) {
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
    u.misc = glm::vec4(cs.exposure, settings.particles.radiusScale, impostorNormal,
                       settings.particles.minPixels);
    u.subpixel = glm::vec4(settings.particles.haloPixels, 0.0f, 0.0f, 0.0f);
    return u;
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
void compilePrograms(ProgramCache& programs, const Settings& settings, bool emits,
                     bool emissiveLight, bool atmosphere) {
    for (const ProgramVariant& v : programVariants(settings, emits, emissiveLight, atmosphere)) {
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

// What upload() puts on the device: the scene's buffers, and the per-set work's draws.
struct Uploaded {
    SceneBuffers scene;
    PerSetDraws draws;
    FrameUniforms uniforms{};  // what scene.uniforms holds
};

// The frame uniforms, the materials and the per-set work's draws (per_set.h), uploaded.
Uploaded upload(DeviceState& d, const core::RenderInput& in, const core::Camera& camera,
                const Settings& settings, core::Frame& frame) {
    const auto start = Clock::now();
    const LightFrustum light =
        fitLightFrustum(in.particles.boundsMin, in.particles.boundsMax, in.scene.camera.position,
                        in.scene.light.direction, settings.shadowMap.resolution);
    const FrameUniforms uniforms = makeUniforms(in.scene, camera, settings, light);
    const GpuMaterials gpuMaterials = packMaterials(in.materials);
    const std::size_t texels = gpuMaterials.texels.size() / 3;
    checkBufferLimits(in, d, 0, texels, settings.perSet);
    Uploaded out{
        .scene = {.uniforms = gl::Buffer::of(std::span<const FrameUniforms>(&uniforms, 1)),
                  .particles = nullptr,
                  .texels = gl::BufferTexture::of(std::span<const float>(gpuMaterials.texels),
                                                  gl::BufferFormat::RGB32F),
                  .materials = gl::Buffer::of(std::span<const GpuMaterial>(gpuMaterials.records)),
                  .draw = {},
                  .ellipsoids = nullptr,
                  .droplets = std::nullopt,
                  .bodySpheres = std::nullopt,
                  .bodyMask = std::nullopt},
        .draws = {}};
    const double sceneMs = msSince(start);
    out.draws = d.perSet(settings).prepare(
        d.programs, in, camera, settings,
        [&](std::size_t records) { checkBufferLimits(in, d, records, texels, settings.perSet); },
        frame);
    out.uniforms = uniforms;
    out.scene.particles = out.draws.particles;
    out.scene.draw = out.draws.draw;
    out.scene.ellipsoids = out.draws.ellipsoids;
    out.scene.droplets = out.draws.droplets;
    out.scene.bodySpheres = out.draws.bodySpheres;
    out.scene.bodyMask = out.draws.bodyMask;
    frame.timingsMs["upload"] += sceneMs;  // the uniforms and materials too
    return out;
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
    double aoRadius = 0.0;                                // light.ao_radius
    const OcclusionGridBuffers* occlusionGrid = nullptr;  // ao.method = "traced": its spheres
    // Whether the emissive pass runs (usesEmissiveLight), and, for "point_lights", the lights.
    bool emissiveLight = false;
    std::vector<PointLight> pointLights = {};
    FrameUniforms uniforms{};  // the frame's ("ssem_target" widens them for its target)
    // A body's atmosphere (its steps as atmosphere.steps says), when the scene has one.
    std::optional<core::Atmosphere> atmosphere = std::nullopt;
};

// Whether the frame runs the occlusion pass: a method, and a reach (light.ao_radius) to look
// within; without one the ambient term is open everywhere.
bool occludes(const PassInputs& in) {
    return usesAmbientOcclusion(in.settings) && in.aoRadius > 0.0;
}

// The occlusion pass over `surface` and `normalUv`, with its second depth layer drawn first
// where ao.layers asks for one, or its rays traced through the frame's grid.
gl::Texture occlusionOf(const PassInputs& in, const gl::Texture& surface,
                        const gl::Texture& normalUv) {
    std::optional<gl::Texture> back;
    if (usesBackLayer(in.settings.ao))
        back.emplace(runBackLayerPass(in.programs, in.scene, surface, in.settings.depth));
    return runAmbientOcclusionPass(in.programs, surface, normalUv, in.settings.ao, in.aoRadius,
                                   back ? &*back : nullptr, in.occlusionGrid);
}

// The frame's resources after its passes (frame_graph.h), and the timer query of each pass
// that ran.
struct PassTargets {
    FrameResources resources;
    std::vector<std::pair<const char*, gl::TimerQuery>> timers;
};

// What the shade pass reads, from the resources' current versions (FrameResources, or a pass's
// PassResources).
template <typename Resources>
ShadeInputs shadeInputs(const PassInputs& in, const Resources& r) {
    ShadeInputs s;
    s.normalUv = &r.read(Resource::NormalUv);
    s.emissionBuffer = &r.read(Resource::Emission);
    s.emission = in.emits;
    s.surface = &r.read(Resource::Surface);
    s.depth = &r.gbuffer().depth;
    s.depthMode = in.settings.depth;
    s.shadowMap = r.find(Resource::ShadowMap);
    s.shadows = in.settings.shadows;
    s.shadowSettings = in.settings.shadowMap;
    s.spheres = in.spheres;
    s.ambientOcclusion = r.find(Resource::Occlusion);
    s.irradiance = r.find(Resource::Irradiance);
    return s;
}

// One pass of the frame: its timings_ms key, what it reads and writes (frame_graph.h), whether
// the settings need it, and what it does.
struct Pass {
    const char* name;
    std::span<const Resource> reads, writes;
    bool (*runs)(const PassInputs&);
    void (*run)(const PassInputs&, PassResources&);
};

bool always(const PassInputs&) {
    return true;
}

using R = Resource;
constexpr std::array SHADOW_WRITES{R::ShadowMap};
constexpr std::array GBUFFER_WRITES{R::GBuffer, R::NormalUv, R::Emission, R::Surface};
constexpr std::array SURFACE_READS{R::GBuffer, R::NormalUv};
constexpr std::array NORMALS_WRITES{R::NormalUv};
constexpr std::array SSSS_WRITES{R::NormalUv, R::Emission};
constexpr std::array FILTER_WRITES{R::NormalUv, R::Emission, R::Surface};
constexpr std::array AO_READS{R::GBuffer, R::Surface, R::NormalUv};
constexpr std::array AO_WRITES{R::Occlusion};
constexpr std::array EMISSIVE_READS{R::Surface, R::NormalUv, R::Emission};
constexpr std::array EMISSIVE_WRITES{R::Irradiance};
constexpr std::array SHADE_READS{R::GBuffer,   R::NormalUv,  R::Emission,  R::Surface,
                                 R::ShadowMap, R::Occlusion, R::Irradiance};
constexpr std::array SHADE_WRITES{R::Beauty};
constexpr std::array HALO_READS{R::GBuffer, R::Beauty};
constexpr std::array HALO_WRITES{R::Beauty};
constexpr std::array ATMOSPHERE_READS{R::GBuffer, R::Surface, R::Beauty};
constexpr std::array ATMOSPHERE_WRITES{R::Beauty, R::Inscatter};
constexpr std::array POST_READS{R::Beauty};
constexpr std::array POST_WRITES{R::Display};

// The frame's passes, in order (passes.h). A pass that does not run reports 0 ms; a new pass is
// a new row, declaring what it reads and writes.
const Pass PASSES[] = {
    {"shadow",
     {},
     SHADOW_WRITES,
     [](const PassInputs& in) { return usesShadowMap(in.settings.shadows); },
     [](const PassInputs& in, PassResources& r) {
         r.write(R::ShadowMap,
                 runShadowPass(in.programs, in.scene, in.settings.shadows, in.settings.shadowMap));
     }},
    {"gbuffer",
     {},
     GBUFFER_WRITES,
     always,
     [](const PassInputs& in, PassResources& r) {
         r.writeGBuffer(runGBufferPass(in.programs, in.scene, in.width, in.height,
                                       in.settings.depth, in.settings.gbufferFormat));
     }},
    // Not under a depth filter, whose normals are rebuilt from the filtered depth (upload
    // leaves the kernels out then).
    {"normals", SURFACE_READS, NORMALS_WRITES,
     [](const PassInputs& in) {
         return in.gradientGrid != nullptr ||
                (in.kernels != nullptr && (in.kernelDraw.commands || in.kernelDraw.count > 0));
     },
     [](const PassInputs& in, PassResources& r) {
         if (in.gradientGrid)
             r.write(R::NormalUv, runGradientGatherPass(in.programs, in.scene, *in.gradientGrid,
                                                        in.camera, r.gbuffer(), in.settings.depth));
         else
             r.write(R::NormalUv,
                     runGradientNormalPass(in.programs, in.scene, *in.kernels, in.kernelDraw,
                                           r.gbuffer(), in.settings.depth));
     }},
    {"ssss", SURFACE_READS, SSSS_WRITES, [](const PassInputs& in) { return usesSsss(in.settings); },
     [](const PassInputs& in, PassResources& r) {
         auto s = std::make_shared<const SmoothedSurface>(
             runSsssPass(in.programs, r.gbuffer(), r.read(R::NormalUv), in.settings.ssss, in.emits,
                         in.settings.depth));
         r.write(R::NormalUv, s, s->normalUv[s->current]);
         // Without emitters the G-buffer's (zero) emission stands.
         if (s->emission[s->current].id()) r.write(R::Emission, s, s->emission[s->current]);
     }},
    {"surface", SURFACE_READS, FILTER_WRITES,
     [](const PassInputs& in) { return usesSurfaceFilter(in.settings); },
     [](const PassInputs& in, PassResources& r) {
         auto f = std::make_shared<const FilteredSurface>(
             runSurfacePass(in.programs, r.gbuffer(), r.read(R::NormalUv), in.settings.surface));
         r.write(R::NormalUv, f, f->normalUv);
         if (f->surface) r.write(R::Surface, f, *f->surface);
         if (f->emission) r.write(R::Emission, f, *f->emission);
     }},
    {"ao", AO_READS, AO_WRITES, [](const PassInputs& in) { return occludes(in); },
     [](const PassInputs& in, PassResources& r) {
         // ao.depth = "filtered" without a depth filter: the narrow-range filter and its
         // normals for this pass alone (the shade pass keeps its surface).
         if (filtersOcclusionDepth(in.settings)) {
             SurfaceSettings narrowRange = in.settings.surface;
             narrowRange.method = SurfaceMethod::NarrowRange;
             const FilteredSurface f =
                 runSurfacePass(in.programs, r.gbuffer(), r.read(R::NormalUv), narrowRange);
             r.write(R::Occlusion, occlusionOf(in, *f.surface, f.normalUv));
             return;
         }
         r.write(R::Occlusion, occlusionOf(in, r.read(R::Surface), r.read(R::NormalUv)));
     }},
    {"emissive", EMISSIVE_READS, EMISSIVE_WRITES,
     [](const PassInputs& in) { return in.emissiveLight; },
     [](const PassInputs& in, PassResources& r) {
         r.write(R::Irradiance,
                 runEmissivePass(in.programs, r.read(R::Surface), r.read(R::NormalUv),
                                 r.read(R::Emission), in.settings.emissive, in.pointLights,
                                 in.scene, in.uniforms, in.settings.depth));
     }},
    {"shade", SHADE_READS, SHADE_WRITES, always,
     [](const PassInputs& in, PassResources& r) {
         r.write(R::Beauty, runShadePass(in.programs, shadeInputs(in, r)));
     }},
    // Adds to the beauty in place: the shade pass's texture stays the current version.
    {"halo", HALO_READS, HALO_WRITES,
     [](const PassInputs& in) { return usesHalo(in.settings, in.emits); },
     [](const PassInputs& in, PassResources& r) {
         runHaloPass(in.programs, in.scene, r.gbuffer().surface, r.read(R::Beauty));
     }},
    {"atmosphere", ATMOSPHERE_READS, ATMOSPHERE_WRITES,
     [](const PassInputs& in) { return in.atmosphere.has_value(); },
     [](const PassInputs& in, PassResources& r) {
         auto t = std::make_shared<const AtmosphereTargets>(
             runAtmospherePass(in.programs, {.beauty = &r.read(R::Beauty),
                                             .impostor = &r.gbuffer().surface,
                                             .filtered = &r.read(R::Surface),
                                             .atmosphere = *in.atmosphere,
                                             .camera = in.camera,
                                             .settings = in.settings.atmosphere}));
         r.write(R::Beauty, t, t->beauty);
         r.write(R::Inscatter, t, t->inscatter);
     }},
    {"post", POST_READS, POST_WRITES, always,
     [](const PassInputs& in, PassResources& r) {
         r.write(R::Display,
                 runPostPass(in.programs, r.read(R::Beauty), in.settings.bloom, in.exposure));
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
        PassResources resources(pass.name, t.resources, pass.reads, pass.writes);
        pass.run(in, resources);
        t.timers.back().second.end();
        gl::checkErrors(pass.name);
        gl::checkConversions("pass", pass.name);
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
void readBack(DeviceState& d, const FrameResources& t, bool emits, int w, int h,
              core::Frame& frame) {
    const auto start = Clock::now();
    // Every read queued, then one wait (gl/readback.h).
    enum Slot : std::size_t {
        NORMAL_UV,
        EMISSION,
        SURFACE,
        BEAUTY_SHADOW,
        DISPLAY,
        OCCLUSION,
        IRRADIANCE,
        INSCATTER
    };
    gl::TextureReadback& r = d.readback;
    r.read(NORMAL_UV, t.read(Resource::NormalUv));
    // Without emitters the emission buffer is zero, as the image's channels already are.
    if (emits) r.read(EMISSION, t.read(Resource::Emission));
    r.read(SURFACE, t.read(Resource::Surface));
    r.read(BEAUTY_SHADOW, t.read(Resource::Beauty));
    r.read(DISPLAY, t.read(Resource::Display));
    const gl::Texture* occlusion = t.find(Resource::Occlusion);
    if (occlusion) r.read(OCCLUSION, *occlusion, 1);
    // Without the emissive pass the irradiance is zero, as the image's channels already are.
    const gl::Texture* irradiance = t.find(Resource::Irradiance);
    if (irradiance) r.read(IRRADIANCE, *irradiance);
    // Without an atmosphere the in-scatter is zero, as the image's channels already are.
    const gl::Texture* inscatter = t.find(Resource::Inscatter);
    if (inscatter) r.read(INSCATTER, *inscatter);
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
    if (occlusion) buffers.ambientOcclusion = r.pixels(OCCLUSION);
    if (irradiance) buffers.irradiance = r.pixels(IRRADIANCE);
    if (inscatter) buffers.inscatter = r.pixels(INSCATTER);
    assembleFrame(buffers, frame.image, frame.display);
    frame.timingsMs["readback"] = msSince(start);
}

// ---- Error split ----

// The linear beauty of an RGBA texture read back (rows from the bottom) as an image.
core::Image beautyImage(std::span<const float> rgba, int w, int h) {
    core::Image image(w, h, {"R", "G", "B"});
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t g = (static_cast<std::size_t>(h - 1 - y) * w + x) * 4;
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = rgba[g + c];
        }
    return image;
}

// Frame::split: the shade pass run three more times on the exact surface and light
// (error_split.h) after the frame, untimed.
void renderSplit(DeviceState& d, const PassInputs& in, const FrameResources& t,
                 const core::RenderInput& input, core::Frame& frame) {
    const ExactSurface exact =
        uploadExactSurface(d.programs, *input.exactSurface, input, in.settings);
    const GBuffer& g = exact.gbuffer;
    // The exact surface with the real-time light: its shadow map, its occlusion pass.
    std::optional<gl::Texture> occlusion;
    if (occludes(in)) occlusion.emplace(occlusionOf(in, g.surface, g.normalUv));
    // Its emissive light too.
    std::optional<gl::Texture> irradiance;
    if (in.emissiveLight)
        irradiance.emplace(runEmissivePass(d.programs, g.surface, g.normalUv, g.emission,
                                           in.settings.emissive, in.pointLights, in.scene,
                                           in.uniforms, in.settings.depth));
    ShadeInputs lighting = shadeInputs(in, t);
    lighting.normalUv = &g.normalUv;
    lighting.emissionBuffer = &g.emission;
    lighting.emission = true;
    lighting.surface = &g.surface;
    lighting.depth = &g.depth;
    lighting.ambientOcclusion = occlusion ? &*occlusion : nullptr;
    lighting.irradiance = irradiance ? &*irradiance : nullptr;
    // The real-time surface with the exact light, pixel by pixel: the reference's emissive
    // light too, where the scene asks for it and something emits (else it is 0).
    const gl::Texture* exactIrradiance =
        input.scene.light.emissiveLight && in.emits ? &exact.irradiance : nullptr;
    ShadeInputs surface = shadeInputs(in, t);
    surface.visibility = &exact.visibility;
    surface.ambientOcclusion = &exact.ambientOcclusion;
    surface.irradiance = exactIrradiance;
    // The exact surface with the exact light.
    ShadeInputs shading = lighting;
    shading.visibility = &exact.visibility;
    shading.ambientOcclusion = &exact.ambientOcclusion;
    shading.irradiance = exactIrradiance;
    const std::pair<const char*, const ShadeInputs*> parts[] = {
        {"surface", &surface}, {"lighting", &lighting}, {"shading", &shading}};
    std::vector<gl::Texture> beauty;
    for (const auto& [name, inputs] : parts) beauty.push_back(runShadePass(d.programs, *inputs));
    gl::checkErrors("error split");
    gl::checkConversions("pass", "error split");
    gl::TextureReadback& r = d.readback;
    constexpr std::size_t FIRST_SLOT = 8;  // after readBack's
    for (std::size_t i = 0; i < beauty.size(); ++i) r.read(FIRST_SLOT + i, beauty[i]);
    r.wait();
    for (std::size_t i = 0; i < beauty.size(); ++i)
        frame.split[parts[i].first] =
            beautyImage(r.pixels(FIRST_SLOT + i), frame.image.width(), frame.image.height());
}

}  // namespace

Renderer::Renderer(Device& device, const Settings& settings)
    : mOwner(device), mDevice(*device.mState), mSettings(settings) {
    // A user's shader that does not compile is bad input: said before anything renders.
    if (settings.surface.method == SurfaceMethod::Shader) {
        mDevice.context.makeCurrent();
        userSurfaceProgram(mDevice.programs, settings.surface);
    }
}

void Renderer::settlePerSet() {
    const std::optional<Device::PerSetCheck>& check = mOwner.perSetCheck();
    if (mPerSetNote || !check || check->passed || mSettings.perSet != PerSetDevice::Gpu) return;
    // Settled for the renderer's life: the device's verdict does not change.
    if (mSettings.perSetFallback) {
        mSettings.perSet = PerSetDevice::Cpu;
        mPerSetNote = PerSetNote{
            .fellBack = true,
            .text = fmt::format(" (per-set work on the CPU: the GPU per-set path failed the "
                                "self-check: {})",
                                check->summary)};
    } else {
        mPerSetNote = PerSetNote{
            .fellBack = false,
            .text = fmt::format(" (the GPU per-set path failed the self-check and is kept, "
                                "per_set_fallback = false: {})",
                                check->summary)};
    }
}

void Renderer::recycle(core::Frame&& old) {
    mDevice.spareImage = std::move(old.image);
    mDevice.spareDisplay = std::move(old.display);
}

core::Frame Renderer::render(const core::RenderInput& in) {
    core::throwIfCancelled(in.cancel);
    // A part costs a whole frame's passes: it would save nothing.
    core::requireWholeFrame(in, "real-time");
    DeviceState& d = mDevice;
    d.context.makeCurrent();
    checkLimits(in, mSettings, d);
    const core::Camera camera(in.scene.camera);
    core::Frame frame;
    frame.renderer = "realtime";
    settlePerSet();
    frame.device = d.context.renderer();
    if (mPerSetNote) {
        frame.device += mPerSetNote->text;
        frame.counters["per_set_fallback"] = mPerSetNote->fellBack ? 1.0 : 0.0;
    }
    frame.settings = toJson(mSettings);
    frame.particleCount = in.particles.particles.size();
    for (const std::string& stage : perSetStages()) frame.timingsMs[stage] = 0.0;
    for (const char* stage : {"upload", "pack", "readback"}) frame.timingsMs[stage] = 0.0;
    for (const Pass& pass : PASSES) frame.timingsMs[pass.name] = 0.0;

    // Whether anything emits: otherwise the emission buffer is zero and SSSS leaves it alone.
    const bool emits = sceneEmits(in.particles.particles, in.materials);
    // Compiling programs is set-up, like creating the context: not part of the render time.
    const auto compileStart = Clock::now();
    const bool emissiveLight = usesEmissiveLight(mSettings, in.scene.light.emissiveLight, emits);
    const bool hasAtmosphere =
        std::any_of(in.scene.bodies.begin(), in.scene.bodies.end(),
                    [](const core::BodyDesc& b) { return b.atmosphere.has_value(); });
    compilePrograms(d.programs, mSettings, emits, emissiveLight, hasAtmosphere);
    frame.timingsMs["compile"] = msSince(compileStart);

    const auto totalStart = Clock::now();
    // The atmosphere's shell (its inner radius from the particles, core/atmosphere.h), the
    // level-set radius kept while the particle set stays the same.
    std::optional<core::Atmosphere> atmosphere;
    if (hasAtmosphere) {
        const double level = mSettings.particles.surfaceLevel;
        atmosphere = core::sceneAtmosphere(in.scene, in.particles, [&](std::uint32_t body) {
            return mLevelSetRadius.get(
                in.particles.particles,
                [&] {
                    return core::levelSetRadius(in.particles.particles, in.particles.bodies[body],
                                                level);
                },
                body, level);
        });
    }
    if (atmosphere && mSettings.atmosphere.steps > 0)
        atmosphere->steps = mSettings.atmosphere.steps;
    const Uploaded uploaded = upload(d, in, camera, mSettings, frame);
    PassInputs passInputs{.programs = d.programs,
                          .scene = uploaded.scene,
                          .settings = mSettings,
                          .kernels = uploaded.draws.kernels,
                          .kernelDraw = uploaded.draws.kernelDraw,
                          .width = camera.width(),
                          .height = camera.height()};
    passInputs.emits = emits;
    passInputs.gradientGrid = uploaded.draws.gradientGrid;
    passInputs.camera = in.scene.camera.position;
    passInputs.aoRadius = in.scene.light.aoRadius;
    // ao.method = "traced": its grid of spheres, built and uploaded with the scene ("upload").
    std::optional<OcclusionGridBuffers> occlusionGrid;
    if (occludes(passInputs) && mSettings.ao.method == AoMethod::Traced) {
        const auto gridStart = Clock::now();
        occlusionGrid = uploadOcclusionGrid(d.occlusionGrid.grid(
            in.particles, mSettings.particles, in.scene.camera.position, passInputs.aoRadius));
        passInputs.occlusionGrid = &*occlusionGrid;
        frame.timingsMs["upload"] += msSince(gridStart);
    }
    passInputs.emissiveLight = emissiveLight;
    passInputs.uniforms = uploaded.uniforms;
    passInputs.atmosphere = atmosphere;
    if (emissiveLight && mSettings.emissive.method == EmissiveMethod::PointLights) {
        passInputs.pointLights = pointLights(in.particles, in.materials, in.scene.camera.position);
        frame.counters["point_lights"] = static_cast<double>(passInputs.pointLights.size());
    }
    passInputs.exposure = static_cast<float>(in.scene.camera.exposure);
    frame.counters["gbuffer_bytes"] =
        static_cast<double>(gbufferBytesPerPixel(mSettings.gbufferFormat, mSettings.depth)) *
        camera.width() * camera.height();
    if (mSettings.shadows == ShadowMode::Spheres) {
        passInputs.spheres = occlusionSpheres(in.particles);
        for (auto& s : passInputs.spheres) s.centre -= in.scene.camera.position;
        frame.counters["occlusion_spheres"] = static_cast<double>(passInputs.spheres.size());
    }
    // The per-particle-set work (radii, anisotropy, culling) can take seconds on a large set.
    core::throwIfCancelled(in.cancel);
    const PassTargets targets = runPasses(passInputs);
    readBack(d, targets.resources, emits, camera.width(), camera.height(), frame);
    d.perSet(mSettings).afterFrame(frame);
    for (const auto& [name, query] : targets.timers) frame.timingsMs[name] = query.milliseconds();
    frame.timingsMs["total"] = msSince(totalStart);
    if (in.exactSurface) renderSplit(d, passInputs, targets.resources, in, frame);
    return frame;
}

}  // namespace twinrender::realtime
