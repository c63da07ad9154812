// Helpers shared by the passes (passes.h).
#include "realtime/passes.h"

#include <cctype>
#include <glm/vec2.hpp>

#include "realtime/gl/pipeline.h"

namespace twinrender::realtime {

void SceneBuffers::bind() const {
    uniforms.bindUniform(0);
    particles->bindStorage(0);
    texels.bind(7);
    materials.bindStorage(2);
    if (ellipsoids) ellipsoids->bindStorage(4);
    if (bodyMask) bodyMask->words->bindStorage(1);
}

void SceneBuffers::drawImpostors(ProgramCache& programs, const char* fragment,
                                 const std::vector<std::string>& defines,
                                 const gl::Buffer* frame) const {
    const std::vector<std::string> particleDefines = bodyMaskDefines(bodyMask.has_value(), defines);
    programs.get("impostor.vert", fragment, impostorDefines(ellipsoids != nullptr, particleDefines))
        .use();
    bind();
    if (frame) frame->bindUniform(0);
    draw.draw();
    if (droplets) {
        programs.get("impostor.vert", fragment, impostorDefines(true, particleDefines)).use();
        droplets->ellipsoids->bindStorage(4);
        droplets->draw.draw();
    }
    if (bodySpheres) {
        programs.get("impostor.vert", fragment, bodySphereDefines(defines)).use();
        bodySpheres->records->bindStorage(0);
        bodySpheres->draw.draw();
        particles->bindStorage(0);
    }
}

void DrawList::draw() const {
    if (commands)
        gl::drawTrianglesIndirect(commands->id(), offset);
    else
        gl::drawTriangles(static_cast<int>(6 * count), static_cast<int>(6 * first));
}

std::vector<std::string> impostorDefines(bool ellipsoids, std::vector<std::string> defines) {
    if (ellipsoids) defines.emplace_back("ELLIPSOID");
    return defines;
}

std::vector<std::string> bodySphereDefines(std::vector<std::string> defines) {
    defines.emplace_back("BODY_SPHERE");
    return defines;
}

std::vector<std::string> bodyMaskDefines(bool bodyMask, std::vector<std::string> defines) {
    if (bodyMask) defines.emplace_back("BODY_MASK");
    return defines;
}

const char* depthDefine(DepthMode mode) {
    switch (mode) {
        case DepthMode::Standard:
            return "DEPTH_STANDARD";
        case DepthMode::Log:
            return "DEPTH_LOG";
        case DepthMode::Reversed:
            return "DEPTH_REVERSED";
    }
    return "DEPTH_LOG";
}

std::string shadowDefine(ShadowMode mode) {
    std::string define = "SHADOWS_";
    for (const char c : toString(mode))
        define += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return define;
}

std::vector<std::string> shadeDefines(ShadowMode mode, const ShadowMapSettings& shadowMap,
                                      bool emission, bool ambientOcclusion, bool emissiveLight) {
    std::vector<std::string> defines = {shadowDefine(mode)};
    if (mode == ShadowMode::Esm && shadowMap.esmForm == EsmForm::Seed)
        defines.emplace_back("ESM_SEED");
    if (emission) defines.emplace_back("EMISSION");
    if (ambientOcclusion) defines.emplace_back("AMBIENT_OCCLUSION");
    if (emissiveLight) defines.emplace_back("EMISSIVE_LIGHT");
    return defines;
}

gl::PipelineState coveredOnlyState(DepthMode mode) {
    // The background holds the cleared depth (1, or 0 reversed); every covered pixel is nearer.
    return {.depthTest = mode == DepthMode::Reversed ? gl::DepthTest::Less : gl::DepthTest::Greater,
            .depthWrite = false,
            .clipDepth = mode == DepthMode::Reversed ? gl::ClipDepth::ZeroToOne
                                                     : gl::ClipDepth::MinusOneToOne};
}

float coveredOnlyDepth(DepthMode mode) {
    // Window depth 1 is clip depth +1 in [-1, 1]; window depth 0 is clip depth 0 in [0, 1].
    return mode == DepthMode::Reversed ? 0.0f : 1.0f;
}

void blurSeparably(const gl::Program& blur, int radius, const gl::Texture (&open)[2],
                   const gl::Framebuffer (&targets)[2]) {
    blur.use();
    blur.set("uRadius", radius);
    blur.set("uDepth", 0.0f);
    for (int pass = 0; pass < 2; ++pass) {
        open[pass].bind(0);
        blur.set("uDirection", pass == 0 ? glm::ivec2(1, 0) : glm::ivec2(0, 1));
        targets[1 - pass].bind();
        gl::drawFullscreenTriangle();
    }
}

}  // namespace twinrender::realtime
