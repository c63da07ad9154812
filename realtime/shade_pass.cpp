// The shading pass (shaders/shade.frag): core's shading model on the smoothed buffers.
#include <fmt/format.h>

#include "realtime/gl/error.h"
#include "realtime/gl/pipeline.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

namespace {
constexpr int MAX_SPHERES = 20;  // shade.frag; bodies over 5 % of the particles are at most 19
}

gl::Texture runShadePass(ProgramCache& programs, const ShadeInputs& in) {
    const int w = in.surface->width(), h = in.surface->height();
    // Linear filtering for the bloom's bright pass; every other read is a texelFetch.
    gl::Texture beauty(w, h, gl::Format::RGBA32F, gl::Filter::Linear);
    gl::Framebuffer framebuffer("shade", {{&beauty}}, gl::Attachment{in.depth});
    framebuffer.bind();
    framebuffer.clearColor(0, glm::vec4(0.0f));  // the background: black, visibility 0
    gl::setPipelineState(coveredOnlyState(in.depthMode));

    // With a visibility per pixel no shadow mode is read: its define takes the mode's place.
    const ShadowMode shadows = in.visibility ? ShadowMode::None : in.shadows;
    std::vector<std::string> defines =
        shadeDefines(shadows, in.shadowSettings, in.emission, in.ambientOcclusion != nullptr,
                     in.irradiance != nullptr);
    if (in.visibility) defines.front() = "VISIBILITY_TEXTURE";
    const gl::Program& program = programs.get("fullscreen.vert", "shade.frag", defines);
    program.use();
    in.normalUv->bind(0);
    in.emissionBuffer->bind(1);
    in.surface->bind(2);
    if (in.visibility)
        in.visibility->bind(3);
    else if (in.shadowMap)
        in.shadowMap->bind(3);
    if (in.ambientOcclusion) in.ambientOcclusion->bind(4);
    if (in.irradiance) in.irradiance->bind(5);
    if (usesFilteredShadowMap(shadows)) {
        program.set("uExponents", shadowExponents(in.shadows, in.shadowSettings));
        program.set("uBleedReduction", static_cast<float>(in.shadowSettings.vsmBleedReduction));
    }
    if (shadows == ShadowMode::Spheres) {
        if (in.spheres.size() > MAX_SPHERES)
            throw gl::Error(
                fmt::format("{} occlusion spheres, at most {}", in.spheres.size(), MAX_SPHERES));
        std::vector<glm::vec4> spheres;
        for (const auto& s : in.spheres)
            spheres.emplace_back(glm::vec3(s.centre), static_cast<float>(s.radius));
        program.set("uSphereCount", static_cast<int>(spheres.size()));
        program.set("uSpheres", std::span<const glm::vec4>(spheres));
        for (std::size_t i = 0; i < in.spheres.size(); ++i)
            program.set(fmt::format("uSphereBodies[{}]", i),
                        static_cast<float>(in.spheres[i].body));
    }
    program.set("uDepth", coveredOnlyDepth(in.depthMode));
    gl::drawFullscreenTriangle();
    gl::setPipelineState({});
    return beauty;
}

}  // namespace twinrender::realtime
