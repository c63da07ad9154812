// The G-buffer pass: impostors from the camera (shaders/impostor.vert, shaders/gbuffer.frag).
#include <limits>

#include "realtime/gl/pipeline.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

std::size_t gbufferBytesPerPixel(GBufferFormat format, DepthMode mode) {
    const std::size_t colour = format == GBufferFormat::Compact ? 8 + 8 + 16 : 3 * 16;
    (void)mode;  // Depth24 and Depth32F both take 4 bytes a pixel
    return colour + 4;
}

GBuffer runGBufferPass(ProgramCache& programs, const SceneBuffers& scene, int width, int height,
                       DepthMode mode, GBufferFormat format) {
    // "compact": the normal + uv and the emission in half floats, as the seed's renderer kept
    // them; the surface target (eye depth, body, radius, material) stays 32-bit: a body index
    // above 2048 and a depth's relative precision need it.
    const gl::Format small =
        format == GBufferFormat::Compact ? gl::Format::RGBA16F : gl::Format::RGBA32F;
    GBuffer g{gl::Texture(width, height, small),
              gl::Texture(width, height, small),
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
