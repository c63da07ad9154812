// realtime.particles.normal = "gradient": every particle's kernel gradient added at the surface
// points of the G-buffer, splatted (per_set = "cpu": shaders/support.vert,
// shaders/gradient_splat.frag) or gathered through the per-set grid (per_set = "gpu":
// shaders/gradient_gather.comp), then turned into the normal (shaders/gradient_resolve.frag).
#include "realtime/gl/pipeline.h"
#include "realtime/passes.h"
#include "realtime/per_set_gpu.h"

namespace twinrender::realtime {

namespace {
// The normal from the summed gradient, where it is not zero; the G-buffer's own elsewhere.
gl::Texture resolveGradient(ProgramCache& programs, const gl::Texture& gradient,
                            const GBuffer& gbuffer, DepthMode mode) {
    gl::Texture normalUv(gradient.width(), gradient.height(), gl::Format::RGBA32F);
    gl::Framebuffer target("gradient resolve", {{&normalUv}}, gl::Attachment{&gbuffer.depth});
    target.bind();
    gl::setPipelineState(coveredOnlyState(mode));
    const gl::Program& resolve = programs.get("fullscreen.vert", "gradient_resolve.frag", {});
    resolve.use();
    resolve.set("uDepth", coveredOnlyDepth(mode));
    gbuffer.normalUv.bind(0);
    gradient.bind(1);
    gl::drawFullscreenTriangle();
    gl::setPipelineState({});
    return normalUv;
}
}  // namespace

gl::Texture runGradientNormalPass(ProgramCache& programs, const SceneBuffers& scene,
                                  const gl::Buffer& kernels, const DrawList& kernelDraw,
                                  const GBuffer& gbuffer, DepthMode mode) {
    const int w = gbuffer.surface.width(), h = gbuffer.surface.height();
    gl::Texture gradient(w, h, gl::Format::RGBA32F);
    {
        // The G-buffer's depth, read only: a splat runs only where the surface does not lie
        // in front of its whole support (support.vert).
        gl::Framebuffer target("gradient splat", {{&gradient}}, gl::Attachment{&gbuffer.depth});
        target.bind();
        target.clearColor(0, glm::vec4(0.0f));
        const bool reversed = mode == DepthMode::Reversed;
        gl::setPipelineState(
            {.depthTest = reversed ? gl::DepthTest::Greater : gl::DepthTest::Less,
             .depthWrite = false,
             .depthClamp = true,
             .clipDepth = reversed ? gl::ClipDepth::ZeroToOne : gl::ClipDepth::MinusOneToOne,
             .additiveBlend = true});
        programs.get("support.vert", "gradient_splat.frag", {depthDefine(mode)}).use();
        scene.bind();
        kernels.bindStorage(3);
        gbuffer.surface.bind(0);
        kernelDraw.draw();
    }
    return resolveGradient(programs, gradient, gbuffer, mode);
}

gl::Texture runGradientGatherPass(ProgramCache& programs, const SceneBuffers& scene,
                                  GpuPerSet& perSet, const glm::dvec3& camera,
                                  const GBuffer& gbuffer, DepthMode mode) {
    gl::Texture gradient(gbuffer.surface.width(), gbuffer.surface.height(), gl::Format::RGBA32F);
    scene.bind();  // the frame's uniforms
    if (scene.bodyMask)
        perSet.gatherGradient(programs, gbuffer.surface, gradient, camera, scene.bodyMask->words,
                              scene.bodyMask->reachesOthers);
    else
        perSet.gatherGradient(programs, gbuffer.surface, gradient, camera);
    return resolveGradient(programs, gradient, gbuffer, mode);
}

}  // namespace twinrender::realtime
