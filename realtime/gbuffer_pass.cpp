// The G-buffer pass: impostors from the camera (shaders/impostor.vert, shaders/gbuffer.frag).
#include <limits>

#include "realtime/gl/pipeline.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

GBuffer runGBufferPass(ProgramCache& programs, const SceneBuffers& scene, int width, int height,
                       DepthMode mode) {
    GBuffer g{gl::Texture(width, height, gl::Format::RGBA32F),
              gl::Texture(width, height, gl::Format::RGBA32F),
              gl::Texture(width, height, gl::Format::RGBA32F),
              // "standard" is what a default framebuffer gives: 24-bit fixed point.
              gl::Texture(width, height,
                          mode == DepthMode::Standard ? gl::Format::Depth24 : gl::Format::Depth32F),
              {}};
    g.framebuffer = gl::Framebuffer("gbuffer", {{&g.normalUv}, {&g.emission}, {&g.surface}},
                                    gl::Attachment{&g.depth});
    g.framebuffer.bind();
    g.framebuffer.clearColor(0, glm::vec4(0.0f));
    g.framebuffer.clearColor(1, glm::vec4(0.0f));
    g.framebuffer.clearColor(2,
                             glm::vec4(std::numeric_limits<float>::infinity(), -1.0f, 0.0f, 0.0f));
    const bool reversed = mode == DepthMode::Reversed;
    g.framebuffer.clearDepth(reversed ? 0.0f : 1.0f);
    gl::setPipelineState(
        {.depthTest = reversed ? gl::DepthTest::Greater : gl::DepthTest::Less,
         .depthWrite = true,
         .depthClamp = true,
         .clipDepth = reversed ? gl::ClipDepth::ZeroToOne : gl::ClipDepth::MinusOneToOne});
    scene.drawImpostors(programs, "gbuffer.frag", {depthDefine(mode)});
    gl::setPipelineState({});
    return g;
}

}  // namespace twinrender::realtime
