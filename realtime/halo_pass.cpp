// The halo pass (realtime.particles.halo_pixels): sub-pixel emitters' flux as Gaussian halos,
// added to the shaded linear beauty (shaders/halo.vert, halo.frag).
#include "realtime/gl/framebuffer.h"
#include "realtime/gl/pipeline.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

void runHaloPass(ProgramCache& programs, const SceneBuffers& scene, const gl::Texture& surface,
                 const gl::Texture& beauty) {
    gl::Framebuffer framebuffer("halo", {{&beauty}});
    framebuffer.bind();
    gl::setPipelineState({.additiveBlend = true});
    programs.get("halo.vert", "halo.frag", bodyMaskDefines(scene.bodyMask.has_value(), {})).use();
    scene.bind();
    surface.bind(2);
    scene.draw.draw();
    gl::setPipelineState({});
}

}  // namespace twinrender::realtime
