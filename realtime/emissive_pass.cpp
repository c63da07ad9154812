// The emissive pass (shaders/emissive_points.frag, or shaders/ssem.frag then
// shaders/ao_blur.frag twice): the real-time estimate of the irradiance that emitting surfaces
// cast (light.emissive_light), which the shade pass adds as albedo E / pi.
#include <fmt/format.h>

#include <algorithm>
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

void drawScreenSpace(ProgramCache& programs, const EmissiveSettings& settings) {
    const gl::Program& program = programs.get("fullscreen.vert", "ssem.frag", {});
    program.use();
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

std::vector<EmissiveProgram> emissivePrograms(const EmissiveSettings& settings) {
    switch (settings.method) {
        case EmissiveMethod::None:
            return {};
        case EmissiveMethod::PointLights:
            return {{.fragment = "emissive_points.frag"}};
        case EmissiveMethod::Ssem:
            break;
    }
    std::vector<EmissiveProgram> out = {{.fragment = "ssem.frag"}};
    if (settings.blur == EmissiveBlur::DepthAware)
        out.push_back({.fragment = "ao_blur.frag", .defines = {"AO_DEPTH_AWARE", "RGB"}});
    return out;
}

gl::Texture runEmissivePass(ProgramCache& programs, const gl::Texture& surface,
                            const gl::Texture& normalUv, const gl::Texture& emission,
                            const EmissiveSettings& settings,
                            const std::vector<PointLight>& emitters) {
    const int w = surface.width(), h = surface.height();
    gl::Texture open[2] = {gl::Texture(w, h, gl::Format::RGBA32F),
                           gl::Texture(w, h, gl::Format::RGBA32F)};
    gl::Framebuffer targets[2] = {gl::Framebuffer("emissive", {{&open[0]}}),
                                  gl::Framebuffer("emissive blur", {{&open[1]}})};
    gl::setPipelineState({});
    normalUv.bind(0);
    emission.bind(1);
    surface.bind(2);
    targets[0].bind();
    if (settings.method != EmissiveMethod::Ssem) {
        drawPointLights(programs, emitters);
        return std::move(open[0]);
    }
    drawScreenSpace(programs, settings);
    if (settings.blur == EmissiveBlur::None) return std::move(open[0]);

    const EmissiveProgram blurProgram = emissivePrograms(settings).back();
    const gl::Program& blur =
        programs.get("fullscreen.vert", blurProgram.fragment, blurProgram.defines);
    blur.use();
    blur.set("uRadius", settings.blurRadius);
    blur.set("uDepth", 0.0f);
    // Horizontal into the second target, vertical back into the first.
    for (int pass = 0; pass < 2; ++pass) {
        open[pass].bind(0);
        blur.set("uDirection", pass == 0 ? glm::ivec2(1, 0) : glm::ivec2(0, 1));
        targets[1 - pass].bind();
        gl::drawFullscreenTriangle();
    }
    return std::move(open[0]);
}

}  // namespace twinrender::realtime
