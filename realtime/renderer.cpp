#include "realtime/renderer.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <optional>
#include <span>

#include "core/camera.h"
#include "core/error.h"
#include "realtime/gl/context.h"
#include "realtime/gl/error.h"
#include "realtime/gl/pipeline.h"
#include "realtime/gl/timer_query.h"
#include "realtime/gpu_scene.h"
#include "realtime/light_frustum.h"
#include "realtime/occlusion_culling.h"
#include "realtime/octahedral.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

bool usesShadowMap(ShadowMode mode) {
    return mode == ShadowMode::Map || mode == ShadowMode::Pcf;
}
bool usesSsss(const SsssSettings& s) {
    return s.enabled && s.radiusScale > 0.0;
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
                             settings.shadowMap.pcfRadius, 0.0);
    const bool blend = settings.particles.normal == NormalModel::Blend;
    u.misc = glm::vec4(cs.exposure, settings.particles.radiusScale,
                       blend ? settings.particles.sphereNormalWeight : 0.0, 0.0);
    (void)particles;
    return u;
}

// Occlusion culling assumes that every ray starts outside all spheres. Rays start at the near
// plane; every point of the frustum in front of it lies within nearReach of the eye, so no
// sphere reaching into that ball means the near plane cannot cut a body open.
bool cullingIsExact(const core::ParticleSet& ps, const core::Camera& camera, double radiusScale) {
    const double t = camera.tanHalfFovY();
    const double nearReach =
        camera.settings().near * std::sqrt(1.0 + t * t * (1.0 + camera.aspect() * camera.aspect()));
    for (std::size_t i = 0; i < ps.size(); ++i)
        if (glm::length(glm::dvec3(ps.position[i]) - camera.position()) - radiusScale * ps.h[i] <=
            nearReach)
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

// Reads an RGBA32F texture, bottom row first, into `out` (resized; kept by the device between
// frames, so that its pages are not faulted in again every frame).
void readTexture(const gl::Texture& texture, const char* name, std::vector<float>& out) {
    gl::Framebuffer fb(name, {{&texture}});
    out.resize(static_cast<std::size_t>(texture.width()) * texture.height() * 4);
    fb.readInto(0, 4, out);
}

}  // namespace

struct DeviceState {
    explicit DeviceState(const gl::Context& c) : context(c) {}
    const gl::Context& context;
    ProgramCache programs;
    gl::Limits limits;
    OcclusionCuller culler;  // keeps the last particle set's answer (view-independent)
    FieldNormalCache fieldNormals;  // the same for the G-buffer's field normal models
    // Read-back buffers, RGBA floats, kept between frames.
    std::vector<float> normalUv, emission, surface, beautyShadow, display;
    // Images handed back by Renderer::recycle, reused when the size and channels match.
    core::Image spareImage, spareDisplay;
};

Device::Device(const gl::Context& context) : mState(std::make_unique<DeviceState>(context)) {
    context.makeCurrent();
    mState->limits = gl::queryLimits();
}

Device::~Device() = default;

Renderer::Renderer(Device& device, const Settings& settings)
    : mDevice(*device.mState), mSettings(settings) {}

void Renderer::recycle(core::Frame&& old) {
    mDevice.spareImage = std::move(old.image);
    mDevice.spareDisplay = std::move(old.display);
}

namespace {

// `spare` when it has the size and channels asked for (its values are stale), else a new
// image of zeros.
core::Image reuseOrCreate(core::Image& spare, int w, int h, std::vector<std::string> channels) {
    if (spare.width() == w && spare.height() == h && spare.channelNames() == channels)
        return std::move(spare);
    return core::Image(w, h, std::move(channels));
}

}  // namespace

core::Frame Renderer::render(const core::RenderInput& input) {
    DeviceState& m = mDevice;
    const Settings& settings = mSettings;
    const core::Scene& scene = input.scene;
    const core::SceneParticles& particles = input.particles;
    const std::vector<core::Material>& materials = input.materials;
    m.context.makeCurrent();
    const core::Camera camera(scene.camera);
    const int w = camera.width(), h = camera.height();
    const gl::Limits& limits = m.limits;
    if (w > limits.maxTextureSize || h > limits.maxTextureSize || w > limits.maxViewportWidth ||
        h > limits.maxViewportHeight)
        throw core::InputError(fmt::format(
            "{}: the image of {}x{} pixels exceeds the GL device's limit of {}x{} ({}); lower "
            "camera.width / camera.height",
            scene.file.string(), w, h, std::min(limits.maxTextureSize, limits.maxViewportWidth),
            std::min(limits.maxTextureSize, limits.maxViewportHeight), m.context.renderer()));
    if (usesShadowMap(settings.shadows) && settings.shadowMap.resolution > limits.maxTextureSize)
        throw core::InputError(fmt::format(
            "{}: realtime.shadow_map.resolution = {} exceeds the GL device's texture limit {} ({})",
            scene.file.string(), settings.shadowMap.resolution, limits.maxTextureSize,
            m.context.renderer()));
    for (std::size_t i = 0; i < particles.particles.size(); ++i)
        if (particles.particles.material[i] >= materials.size())
            throw core::InputError(fmt::format(
                "{}: particle {} has material {} but the scene has {}", scene.file.string(), i,
                particles.particles.material[i], materials.size()));

    core::Frame frame;
    frame.renderer = "realtime";
    frame.device = m.context.renderer();
    frame.settings = toJson(settings);
    frame.particleCount = particles.particles.size();
    for (const char* stage :
         {"cull", "upload", "shadow", "gbuffer", "ssss", "shade", "post", "readback"})
        frame.timingsMs[stage] = 0.0;

    // Whether anything emits: otherwise the emission buffer is zero and SSSS leaves it alone.
    const bool emits = sceneEmits(particles.particles, materials);

    // Compiling programs is set-up, like creating the context: not part of the render time.
    const auto compileStart = Clock::now();
    {
        ProgramCache& p = m.programs;
        if (usesShadowMap(settings.shadows)) p.get("impostor.vert", "shadow.frag", {"SHADOW_PASS"});
        p.get("impostor.vert", "gbuffer.frag", {depthDefine(settings.depth)});
        if (usesSsss(settings.ssss)) {
            std::vector<std::string> defines;
            if (settings.ssss.separable) defines.emplace_back("SEPARABLE");
            if (emits) defines.emplace_back("EMISSION");
            p.get("fullscreen.vert", "ssss.frag", defines);
        }
        gl::finish();
    }
    frame.timingsMs["compile"] = msSince(compileStart);

    const auto totalStart = Clock::now();

    // Upload.
    auto stageStart = Clock::now();
    const LightFrustum light =
        fitLightFrustum(particles.boundsMin, particles.boundsMax, scene.camera.position,
                        scene.light.direction, settings.shadowMap.resolution);
    const FrameUniforms uniforms = makeUniforms(scene, camera, particles, settings, light);
    std::span<const std::uint32_t> drawn;
    if (settings.particles.cullHidden &&
        cullingIsExact(particles.particles, camera, settings.particles.radiusScale)) {
        const auto cullStart = Clock::now();
        drawn = m.culler.unoccluded(particles.particles, settings.particles.radiusScale);
        frame.timingsMs["cull"] = msSince(cullStart);
    }
    frame.counters["particles_drawn"] =
        static_cast<double>(drawn.empty() ? particles.particles.size() : drawn.size());
    std::span<const FieldNormal> fieldNormalModels;
    if (settings.particles.normal == NormalModel::Field)
        fieldNormalModels =
            m.fieldNormals.normals(particles.particles, settings.particles.radiusScale, drawn);
    const std::vector<GpuParticle> gpuParticles =
        packParticles(particles.particles, scene.camera.position, settings.particles.radiusScale,
                      drawn, fieldNormalModels);
    const GpuMaterials gpuMaterials = packMaterials(materials);
    if (static_cast<long long>(gpuParticles.size() * sizeof(GpuParticle)) >
        limits.maxStorageBlockBytes)
        throw core::InputError(fmt::format(
            "{}: {} particles take {} MB, over the GL device's storage-buffer limit of {} MB ({})",
            scene.file.string(), gpuParticles.size(),
            (gpuParticles.size() * sizeof(GpuParticle)) >> 20, limits.maxStorageBlockBytes >> 20,
            m.context.renderer()));
    if (static_cast<long long>(gpuMaterials.texels.size() / 3) > limits.maxTextureBufferTexels)
        throw core::InputError(fmt::format(
            "{}: the material textures hold {} texels, over the GL device's buffer-texture limit "
            "of {} ({}); use smaller texture images",
            scene.file.string(), gpuMaterials.texels.size() / 3, limits.maxTextureBufferTexels,
            m.context.renderer()));
    SceneBuffers buffers{gl::Buffer::of(std::span<const FrameUniforms>(&uniforms, 1)),
                         gl::Buffer::of(std::span<const GpuParticle>(gpuParticles)),
                         gl::BufferTexture::of(std::span<const float>(gpuMaterials.texels),
                                               gl::BufferFormat::RGB32F),
                         gl::Buffer::of(std::span<const GpuMaterial>(gpuMaterials.records)),
                         gpuParticles.size()};
    gl::checkErrors("upload");
    gl::finish();
    frame.timingsMs["upload"] = msSince(stageStart) - frame.timingsMs["cull"];

    // Passes, each timed by a GL timer query.
    std::vector<std::pair<std::string, gl::TimerQuery>> timers;
    {
        // llvmpipe answers the first timer query around rendering with a timestamp instead of
        // an elapsed time; a query around a tiny clear absorbs that.
        gl::Texture texture(1, 1, gl::Format::R32F);
        gl::Framebuffer framebuffer("timer warm-up", {{&texture}});
        gl::TimerQuery warmUp;
        warmUp.begin();
        framebuffer.bind();
        framebuffer.clearColor(0, glm::vec4(0.0f));
        warmUp.end();
        warmUp.milliseconds();
    }
    auto pass = [&](const char* name, auto&& body) {
        timers.emplace_back(name, gl::TimerQuery());
        timers.back().second.begin();
        body();
        timers.back().second.end();
        gl::checkErrors(name);
    };

    std::optional<gl::Texture> shadowMap;
    if (usesShadowMap(settings.shadows))
        pass("shadow", [&] {
            shadowMap.emplace(runShadowPass(m.programs, buffers, settings.shadowMap.resolution));
        });

    std::optional<GBuffer> gbuffer;
    pass("gbuffer",
         [&] { gbuffer.emplace(runGBufferPass(m.programs, buffers, w, h, settings.depth)); });

    std::optional<SmoothedSurface> smoothed;
    if (usesSsss(settings.ssss))
        pass("ssss", [&] {
            smoothed.emplace(
                runSsssPass(m.programs, *gbuffer, settings.ssss, emits, settings.depth));
        });

    ShadeInputs shadeInputs;
    shadeInputs.normalUv = smoothed ? &smoothed->resultNormalUv() : &gbuffer->normalUv;
    shadeInputs.emissionBuffer =
        smoothed ? &smoothed->resultEmission(*gbuffer) : &gbuffer->emission;
    shadeInputs.emission = emits;
    shadeInputs.surface = &gbuffer->surface;
    shadeInputs.depth = &gbuffer->depth;
    shadeInputs.depthMode = settings.depth;
    shadeInputs.shadowMap = shadowMap ? &*shadowMap : nullptr;
    shadeInputs.shadows = settings.shadows;
    if (settings.shadows == ShadowMode::Spheres) {
        shadeInputs.spheres = occlusionSpheres(particles);
        for (auto& s : shadeInputs.spheres) s.centre -= scene.camera.position;
        frame.counters["occlusion_spheres"] = static_cast<double>(shadeInputs.spheres.size());
    }
    std::optional<gl::Texture> beauty;
    pass("shade", [&] { beauty.emplace(runShadePass(m.programs, shadeInputs)); });

    std::optional<gl::Texture> display;
    pass("post", [&] {
        display.emplace(runPostPass(m.programs, *beauty, settings.bloom,
                                    static_cast<float>(scene.camera.exposure)));
    });

    // Read back and assemble the AOV image, top row first.
    stageStart = Clock::now();
    readTexture(*shadeInputs.normalUv, "read normal", m.normalUv);
    // Without emitters the emission buffer is zero, as the image's channels already are.
    if (emits) readTexture(*shadeInputs.emissionBuffer, "read emission", m.emission);
    readTexture(gbuffer->surface, "read surface", m.surface);
    readTexture(*beauty, "read beauty", m.beautyShadow);
    readTexture(*display, "read display", m.display);
    const std::vector<float>& normalUv = m.normalUv;
    const std::vector<float>& emission = m.emission;
    const std::vector<float>& surface = m.surface;
    const std::vector<float>& beautyShadow = m.beautyShadow;
    const std::vector<float>& displayPixels = m.display;

    // The background values of core::aov::makeImage (Z = +inf, id = -1, the rest 0) are
    // written in the same pass as the covered pixels: filling the 15 channels first costs
    // as much as the whole read-back.
    frame.image = reuseOrCreate(m.spareImage, w, h, core::aov::channelNames());
    core::Image& image = frame.image;
    const auto channel = [&](const char* name) { return image.requireChannel(name); };
    const int cR = channel("R"), cG = channel("G"), cB = channel("B"), cA = channel("A"),
              cZ = channel("Z"), cNX = channel("N.X"), cNY = channel("N.Y"), cNZ = channel("N.Z"),
              cU = channel("uv.U"), cV = channel("uv.V"), cId = channel("id"),
              cER = channel("emission.R"), cEG = channel("emission.G"), cEB = channel("emission.B"),
              cShadow = channel("shadow");
    const std::size_t stride = static_cast<std::size_t>(image.channelCount());
    frame.display = reuseOrCreate(m.spareDisplay, w, h, {"R", "G", "B"});
    float* aov = image.pixels().data();
    float* shown = frame.display.pixels().data();
    tbb::parallel_for(0, h, [&](int y) {
        // OpenGL rows run bottom-up; images top-down.
        const std::size_t glRow = static_cast<std::size_t>(h - 1 - y) * w;
        for (int x = 0; x < w; ++x) {
            const std::size_t g = (glRow + x) * 4;
            const std::size_t p = static_cast<std::size_t>(y) * w + x;
            float* d = shown + p * 3;
            d[0] = displayPixels[g + 0];
            d[1] = displayPixels[g + 1];
            d[2] = displayPixels[g + 2];
            const float body = surface[g + 1];
            float* o = aov + p * stride;
            if (body < 0.0f) {
                std::fill(o, o + stride, 0.0f);  // a recycled image holds an older frame
                o[cZ] = std::numeric_limits<float>::infinity();
                o[cId] = -1.0f;
                continue;
            }
            o[cR] = beautyShadow[g + 0];
            o[cG] = beautyShadow[g + 1];
            o[cB] = beautyShadow[g + 2];
            o[cShadow] = beautyShadow[g + 3];
            o[cA] = 1.0f;
            o[cZ] = surface[g + 0];
            o[cId] = body;
            const glm::vec3 n = octDecode({normalUv[g + 0], normalUv[g + 1]});
            o[cNX] = n.x;
            o[cNY] = n.y;
            o[cNZ] = n.z;
            o[cU] = normalUv[g + 2];
            o[cV] = normalUv[g + 3];
            o[cER] = emits ? emission[g + 0] : 0.0f;
            o[cEG] = emits ? emission[g + 1] : 0.0f;
            o[cEB] = emits ? emission[g + 2] : 0.0f;
        }
    });
    frame.timingsMs["readback"] = msSince(stageStart);
    for (const auto& [name, query] : timers) frame.timingsMs[name] = query.milliseconds();
    frame.timingsMs["total"] = msSince(totalStart);
    return frame;
}

}  // namespace twinrender::realtime
