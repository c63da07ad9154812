// Screen-Space Surface Smoothing (shaders/ssss.frag, kernel in shaders/ssss_common.glsl):
// `iterations` times the smart blur, either horizontal then vertical (separable) or the full
// 2-D kernel, ping-ponging between two sets of targets; the G-buffer itself is never written.
#include <optional>

#include "realtime/gl/pipeline.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

SmoothedSurface runSsssPass(ProgramCache& programs, const GBuffer& gbuffer,
                            const gl::Texture& normalUv, const SsssSettings& settings,
                            bool emission, DepthMode mode) {
    const int w = gbuffer.surface.width(), h = gbuffer.surface.height();
    SmoothedSurface s;
    std::optional<gl::Framebuffer> targets[2];
    for (int i = 0; i < 2; ++i) {
        s.normalUv[i] = gl::Texture(w, h, gl::Format::RGBA32F);
        std::vector<gl::Attachment> attachments{{&s.normalUv[i]}};
        if (emission) {
            s.emission[i] = gl::Texture(w, h, gl::Format::RGBA32F);
            attachments.push_back({&s.emission[i]});
        }
        // Background pixels are never read by the next pass or by shade: only covered ones
        // are drawn (coveredOnlyState), the rest keep whatever the texture holds.
        targets[i].emplace("ssss " + std::to_string(i), std::move(attachments),
                           gl::Attachment{&gbuffer.depth});
    }

    std::vector<std::string> defines;
    if (settings.separable) defines.emplace_back("SEPARABLE");
    if (emission) defines.emplace_back("EMISSION");
    const gl::Program& program = programs.get("fullscreen.vert", "ssss.frag", defines);
    program.use();
    program.set("uRadiusScale", static_cast<float>(settings.radiusScale));
    program.set("uDepthLimit", static_cast<float>(settings.depthLimit));
    program.set("uMaxTaps", settings.maxTaps);
    program.set("uDepth", coveredOnlyDepth(mode));
    gl::setPipelineState(coveredOnlyState(mode));
    gbuffer.surface.bind(2);

    const gl::Texture* sourceNormalUv = &normalUv;
    const gl::Texture* sourceEmission = &gbuffer.emission;
    int target = 0;
    auto step = [&](glm::vec2 direction) {
        program.set("uDirection", direction);
        sourceNormalUv->bind(0);
        sourceEmission->bind(1);
        targets[target]->bind();
        gl::drawFullscreenTriangle();
        sourceNormalUv = &s.normalUv[target];
        if (emission) sourceEmission = &s.emission[target];
        s.current = target;
        target = 1 - target;
    };
    for (int i = 0; i < settings.iterations; ++i) {
        if (settings.separable) {
            step({1.0f, 0.0f});
            step({0.0f, 1.0f});
        } else {
            step({0.0f, 0.0f});
        }
    }
    gl::setPipelineState({});
    return s;
}

}  // namespace twinrender::realtime
