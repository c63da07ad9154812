// The shadow pass: orthographic impostors from the light (shaders/impostor.vert with
// SHADOW_PASS, shaders/shadow.frag).
#include "realtime/gl/pipeline.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

gl::Texture runShadowPass(ProgramCache& programs, const SceneBuffers& scene, int resolution) {
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

}  // namespace twinrender::realtime
