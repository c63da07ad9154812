// The shadow pass: orthographic impostors from the light (shaders/impostor.vert with
// SHADOW_PASS, shaders/shadow.frag).
#include "realtime/gl/pipeline.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

void SceneBuffers::bind() const {
    uniforms.bindUniform(0);
    particles.bindStorage(0);
    texels.bind(7);
    materials.bindStorage(2);
}

const char* depthDefine(DepthMode mode) {
    switch (mode) {
        case DepthMode::Standard: return "DEPTH_STANDARD";
        case DepthMode::Log: return "DEPTH_LOG";
        case DepthMode::Reversed: return "DEPTH_REVERSED";
    }
    return "DEPTH_LOG";
}

gl::Texture runShadowPass(ProgramCache& programs, const SceneBuffers& scene, int resolution) {
    gl::Texture map(resolution, resolution, gl::Format::Depth32F);
    gl::Framebuffer framebuffer("shadow", {}, gl::Attachment{&map});
    framebuffer.bind();
    framebuffer.clearDepth(1.0f);
    gl::setPipelineState({.depthTest = gl::DepthTest::Less, .depthWrite = true, .depthClamp = true});
    programs.get("impostor.vert", "shadow.frag", {"SHADOW_PASS"}).use();
    scene.bind();
    gl::drawTriangles(static_cast<int>(6 * scene.particleCount));
    gl::setPipelineState({});
    return map;
}

}  // namespace twinrender::realtime
