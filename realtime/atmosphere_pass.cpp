// The atmosphere pass (shaders/atmosphere.frag): a body's atmosphere (core/atmosphere.h) over
// the shaded frame, each view ray ended where atmosphere.end_point says; the beauty becomes
// surface x T + L_in and L_in is kept for the inscatter AOV channels.
#include <string>
#include <vector>

#include "realtime/gl/pipeline.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

std::vector<std::string> atmosphereDefines(const AtmosphereSettings& settings) {
    switch (settings.endPoint) {
        case AtmosphereEndPoint::Impostor:
            return {"END_IMPOSTOR"};
        case AtmosphereEndPoint::Filtered:
            return {"END_FILTERED"};
        case AtmosphereEndPoint::Sphere:
            return {"END_SPHERE"};
        case AtmosphereEndPoint::Blend:
            return {"END_BLEND"};
    }
    return {"END_FILTERED"};
}

AtmosphereTargets runAtmospherePass(ProgramCache& programs, const AtmosphereInputs& in) {
    const int w = in.beauty->width(), h = in.beauty->height();
    AtmosphereTargets out{.beauty = gl::Texture(w, h, gl::Format::RGBA32F, gl::Filter::Linear),
                          .inscatter = gl::Texture(w, h, gl::Format::RGBA32F)};
    gl::Framebuffer framebuffer("atmosphere", {{&out.beauty}, {&out.inscatter}});
    framebuffer.bind();
    gl::setPipelineState({});
    const core::Atmosphere& a = in.atmosphere;
    const gl::Program& program =
        programs.get("fullscreen.vert", "atmosphere.frag", atmosphereDefines(in.settings));
    program.use();
    program.set("uShell", glm::vec4(a.innerRadius, a.outerRadius, a.scaleHeight, a.phaseG));
    program.set("uScattering", a.scattering);
    program.set("uAbsorption", a.absorption);
    program.set("uSteps", a.steps);
    program.set("uCentre", glm::vec3(a.centre - in.camera));
    program.set("uBody", static_cast<float>(a.body));
    program.set("uBlend", glm::vec2(in.settings.blendNear, in.settings.blendFar));
    in.beauty->bind(0);
    in.impostor->bind(1);
    in.filtered->bind(2);
    gl::drawFullscreenTriangle();
    return out;
}

}  // namespace twinrender::realtime
