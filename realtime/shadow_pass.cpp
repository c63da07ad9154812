// The shadow pass: orthographic impostors from the light (shaders/impostor.vert with
// SHADOW_PASS, shaders/shadow.frag); for the filtered maps ("esm", "vsm", "evsm") the depth
// map is then turned into the map the shade pass filters (shaders/shadow_moments.frag) and
// blurred (shaders/shadow_blur.frag, horizontal then vertical).
#include "realtime/gl/pipeline.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

namespace {

gl::Texture drawDepthMap(ProgramCache& programs, const SceneBuffers& scene, int resolution) {
    gl::Texture map(resolution, resolution, gl::Format::Depth32F);
    gl::Framebuffer framebuffer("shadow", {}, gl::Attachment{&map});
    framebuffer.bind();
    framebuffer.clearDepth(1.0f);
    gl::setPipelineState(
        {.depthTest = gl::DepthTest::Less, .depthWrite = true, .depthClamp = true});
    scene.drawImpostors(programs, "shadow.frag", {"SHADOW_PASS"});
    gl::setPipelineState({});
    return map;
}

// The channels each filtered map needs: ESM one, VSM two, EVSM four, all 32-bit float (the
// exponential warps need its range; realtime/settings.h bounds the exponents to fit it).
gl::Format filteredFormat(ShadowMode mode) {
    return mode == ShadowMode::Esm   ? gl::Format::R32F
           : mode == ShadowMode::Vsm ? gl::Format::RG32F
                                     : gl::Format::RGBA32F;
}

gl::Texture writeMoments(ProgramCache& programs, const gl::Texture& depth, ShadowMode mode,
                         const ShadowMapSettings& settings) {
    gl::Texture moments(depth.width(), depth.height(), filteredFormat(mode), gl::Filter::Linear);
    gl::Framebuffer framebuffer("shadow moments", {{&moments}});
    framebuffer.bind();
    const gl::Program& program = programs.get("fullscreen.vert", "shadow_moments.frag",
                                              shadowMomentsDefines(mode, settings));
    program.use();
    program.set("uExponents", shadowExponents(mode, settings));
    depth.bind(0);
    gl::drawFullscreenTriangle();
    return moments;
}

// Horizontal then vertical, through a second map of the same format.
void blurMap(ProgramCache& programs, gl::Texture& map, ShadowMode mode, double radius) {
    gl::Texture across(map.width(), map.height(), filteredFormat(mode), gl::Filter::Linear);
    gl::Framebuffer toAcross("shadow blur x", {{&across}});
    gl::Framebuffer toMap("shadow blur y", {{&map}});
    const gl::Program& program = programs.get("fullscreen.vert", "shadow_blur.frag");
    program.use();
    program.set("uRadius", static_cast<float>(radius));
    toAcross.bind();
    program.set("uDirection", glm::ivec2(1, 0));
    map.bind(0);
    gl::drawFullscreenTriangle();
    toMap.bind();
    program.set("uDirection", glm::ivec2(0, 1));
    across.bind(0);
    gl::drawFullscreenTriangle();
}

}  // namespace

std::vector<std::string> shadowMomentsDefines(ShadowMode mode, const ShadowMapSettings& settings) {
    if (mode == ShadowMode::Vsm) return {"VSM"};
    if (mode == ShadowMode::Evsm) return {"EVSM"};
    return {settings.esmForm == EsmForm::Seed ? "ESM_SEED" : "ESM_WARP"};
}

glm::vec2 shadowExponents(ShadowMode mode, const ShadowMapSettings& settings) {
    if (mode == ShadowMode::Evsm)
        return {static_cast<float>(settings.evsmPositiveExponent),
                static_cast<float>(settings.evsmNegativeExponent)};
    return {static_cast<float>(settings.esmExponent), 0.0f};
}

gl::Texture runShadowPass(ProgramCache& programs, const SceneBuffers& scene, ShadowMode mode,
                          const ShadowMapSettings& settings) {
    gl::Texture depth = drawDepthMap(programs, scene, settings.resolution);
    if (!usesFilteredShadowMap(mode)) return depth;
    gl::setPipelineState({});
    gl::Texture map = writeMoments(programs, depth, mode, settings);
    if (settings.blurRadius > 0.0) blurMap(programs, map, mode, settings.blurRadius);
    return map;
}

}  // namespace twinrender::realtime
