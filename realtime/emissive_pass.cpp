// The emissive pass (shaders/emissive_points.frag, or shaders/ssem.frag then
// shaders/ao_blur.frag twice; for "ssem_target" the emitter target drawn first with
// shaders/gbuffer.frag's EMITTERS_ONLY): the real-time estimate of the irradiance that emitting
// surfaces cast (light.emissive_light), which the shade pass adds as albedo E / pi.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/ext/matrix_clip_space.hpp>
#include <limits>
#include <numbers>
#include <vector>

#include "core/emitters.h"
#include "realtime/gl/error.h"
#include "realtime/gl/pipeline.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

namespace {

float brightness(const PointLight& light) {
    return light.intensity.r + light.intensity.g + light.intensity.b;
}

void drawPointLights(ProgramCache& programs, const std::vector<PointLight>& emitters) {
    if (emitters.size() > MAX_POINT_LIGHTS)
        throw gl::Error(
            fmt::format("{} point lights, at most {}", emitters.size(), MAX_POINT_LIGHTS));
    std::vector<glm::vec4> spheres, intensities;
    for (const PointLight& e : emitters) {
        spheres.emplace_back(e.centre, e.radius);
        intensities.emplace_back(e.intensity, static_cast<float>(e.body));
    }
    const gl::Program& program = programs.get("fullscreen.vert", "emissive_points.frag", {});
    program.use();
    program.set("uDepth", 0.0f);
    program.set("uEmitterCount", static_cast<int>(emitters.size()));
    if (!emitters.empty()) {
        program.set("uEmitters", std::span<const glm::vec4>(spheres));
        program.set("uIntensities", std::span<const glm::vec4>(intensities));
    }
    gl::drawFullscreenTriangle();
}

// The emitter target: the emitting impostors alone (gbuffer.frag discards what does not emit),
// from the camera with `target`'s wider projection, depth tested as the G-buffer is.
struct EmitterTarget {
    gl::Texture normalUv, emission, surface, depth;
    gl::Framebuffer framebuffer;
};

EmitterTarget drawEmitterTarget(ProgramCache& programs, const SceneBuffers& scene,
                                const FrameUniforms& target, DepthMode mode) {
    const int w = static_cast<int>(target.viewport.x), h = static_cast<int>(target.viewport.y);
    EmitterTarget t{
        gl::Texture(w, h, gl::Format::RGBA32F),
        gl::Texture(w, h, gl::Format::RGBA32F),
        gl::Texture(w, h, gl::Format::RGBA32F),
        gl::Texture(w, h, mode == DepthMode::Standard ? gl::Format::Depth24 : gl::Format::Depth32F),
        {}};
    t.framebuffer = gl::Framebuffer("emitter target", {{&t.normalUv}, {&t.emission}, {&t.surface}},
                                    gl::Attachment{&t.depth});
    t.framebuffer.bind();
    t.framebuffer.clearColor(0, glm::vec4(0.0f));
    t.framebuffer.clearColor(1, glm::vec4(0.0f));
    t.framebuffer.clearColor(2,
                             glm::vec4(std::numeric_limits<float>::infinity(), -1.0f, 0.0f, 0.0f));
    const bool reversed = mode == DepthMode::Reversed;
    t.framebuffer.clearDepth(reversed ? 0.0f : 1.0f);
    gl::setPipelineState(
        {.depthTest = reversed ? gl::DepthTest::Greater : gl::DepthTest::Less,
         .depthWrite = true,
         .depthClamp = true,
         .clipDepth = reversed ? gl::ClipDepth::ZeroToOne : gl::ClipDepth::MinusOneToOne});
    const gl::Buffer uniforms = gl::Buffer::of(std::span<const FrameUniforms>(&target, 1));
    scene.drawImpostors(programs, "gbuffer.frag", emitterTargetDefines(mode), &uniforms);
    gl::setPipelineState({});
    scene.uniforms.bindUniform(0);  // the frame's again, for the passes after
    return t;
}

void drawScreenSpace(ProgramCache& programs, const EmissiveSettings& settings,
                     const FrameUniforms* target = nullptr) {
    const gl::Program& program =
        target ? programs.get("fullscreen.vert", "ssem.frag", {"EMITTER_TARGET"})
               : programs.get("fullscreen.vert", "ssem.frag", {});
    program.use();
    if (target) {
        const float tanY = target->camera.z;
        program.set("uTargetTan", glm::vec2(tanY * target->viewport.x * target->viewport.w, tanY));
        program.set("uTargetSize", glm::vec2(target->viewport.x, target->viewport.y));
    }
    program.set("uDepth", 0.0f);
    program.set("uDirections", settings.directions);
    program.set("uSteps", settings.steps);
    program.set("uMaxPixels", static_cast<float>(settings.maxPixels));
    program.set("uThickness", static_cast<float>(settings.thickness));
    gl::drawFullscreenTriangle();
}

}  // namespace

std::vector<PointLight> pointLights(const core::SceneParticles& particles,
                                    const std::vector<core::Material>& materials,
                                    const glm::dvec3& camera) {
    std::vector<PointLight> out;
    for (const core::EmittingBody& b : core::emittingBodies(particles, materials)) {
        const double area = std::numbers::pi * b.surfaceRadius * b.surfaceRadius;
        out.push_back({.centre = glm::vec3(b.centre - camera),
                       .radius = static_cast<float>(b.surfaceRadius),
                       .intensity = glm::vec3(area * b.meanRadiance),
                       .body = b.body});
    }
    // More bodies than the shader holds: the brightest light the most.
    if (out.size() > MAX_POINT_LIGHTS) {
        std::stable_sort(out.begin(), out.end(), [](const PointLight& a, const PointLight& b) {
            return brightness(a) > brightness(b);
        });
        out.resize(MAX_POINT_LIGHTS);
    }
    return out;
}

FrameUniforms emitterTargetUniforms(const FrameUniforms& frame, const EmissiveSettings& settings,
                                    DepthMode mode) {
    FrameUniforms u = frame;
    const float width = settings.targetAspect ? frame.viewport.x : frame.viewport.y;
    const float height = frame.viewport.y;
    const double tanY = settings.targetFovScale * frame.camera.z;
    const double fovY = 2.0 * std::atan(tanY);
    const double aspect = double(width) / double(height);
    const double near = frame.camera.x, far = frame.camera.y;
    // As makeUniforms (renderer.cpp) builds the camera's.
    u.clipFromView = mode == DepthMode::Reversed
                         ? glm::mat4(glm::perspectiveRH_ZO(fovY, aspect, far, near))
                         : glm::mat4(glm::perspectiveRH_NO(fovY, aspect, near, far));
    u.viewport = glm::vec4(width, height, 1.0f / width, 1.0f / height);
    u.camera.z = static_cast<float>(tanY);
    return u;
}

std::vector<std::string> emitterTargetDefines(DepthMode mode) {
    return {depthDefine(mode), "EMITTERS_ONLY"};
}

std::vector<EmissiveProgram> emissivePrograms(const EmissiveSettings& settings) {
    switch (settings.method) {
        case EmissiveMethod::None:
            return {};
        case EmissiveMethod::PointLights:
            return {{.fragment = "emissive_points.frag"}};
        case EmissiveMethod::Ssem:
        case EmissiveMethod::SsemTarget:
            break;
    }
    std::vector<EmissiveProgram> out = {
        settings.method == EmissiveMethod::SsemTarget
            ? EmissiveProgram{.fragment = "ssem.frag", .defines = {"EMITTER_TARGET"}}
            : EmissiveProgram{.fragment = "ssem.frag"}};
    if (settings.blur == EmissiveBlur::DepthAware)
        out.push_back({.fragment = "ao_blur.frag", .defines = {"AO_DEPTH_AWARE", "RGB"}});
    return out;
}

gl::Texture runEmissivePass(ProgramCache& programs, const gl::Texture& surface,
                            const gl::Texture& normalUv, const gl::Texture& emission,
                            const EmissiveSettings& settings,
                            const std::vector<PointLight>& emitters, const SceneBuffers& scene,
                            const FrameUniforms& frame, DepthMode mode) {
    const int w = surface.width(), h = surface.height();
    gl::Texture open[2] = {gl::Texture(w, h, gl::Format::RGBA32F),
                           gl::Texture(w, h, gl::Format::RGBA32F)};
    gl::Framebuffer targets[2] = {gl::Framebuffer("emissive", {{&open[0]}}),
                                  gl::Framebuffer("emissive blur", {{&open[1]}})};
    std::optional<EmitterTarget> emitterTarget;
    FrameUniforms target;
    if (settings.method == EmissiveMethod::SsemTarget) {
        target = emitterTargetUniforms(frame, settings, mode);
        emitterTarget = drawEmitterTarget(programs, scene, target, mode);
    }
    gl::setPipelineState({});
    normalUv.bind(0);
    emission.bind(1);
    surface.bind(2);
    targets[0].bind();
    if (settings.method == EmissiveMethod::PointLights) {
        drawPointLights(programs, emitters);
        return std::move(open[0]);
    }
    if (emitterTarget) {
        emitterTarget->surface.bind(3);
        emitterTarget->emission.bind(4);
    }
    drawScreenSpace(programs, settings, emitterTarget ? &target : nullptr);
    if (settings.blur == EmissiveBlur::None) return std::move(open[0]);

    const EmissiveProgram blurProgram = emissivePrograms(settings).back();
    const gl::Program& blur =
        programs.get("fullscreen.vert", blurProgram.fragment, blurProgram.defines);
    blurSeparably(blur, settings.blurRadius, open, targets);
    return std::move(open[0]);
}

}  // namespace twinrender::realtime
