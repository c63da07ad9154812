// The ambient occlusion pass (shaders/ao.frag, then shaders/ao_blur.frag twice): screen-space
// occlusion of the ambient term, its reach the scene's light.ao_radius.
#include <vector>

#include "realtime/ao_traced.h"
#include "realtime/blue_noise.h"
#include "realtime/gl/pipeline.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

namespace {

// The blue-noise tile's side (pixels): 64 x 64 ranks, the size dither textures ship at.
constexpr int BLUE_NOISE_SIDE = 64;

// The tile's ranks, made once per process (a few milliseconds).
const std::vector<float>& blueNoiseTile() {
    static const std::vector<float> values = blueNoise(BLUE_NOISE_SIDE);
    return values;
}

}  // namespace

std::vector<std::string> ambientOcclusionDefines(const AoSettings& settings) {
    std::vector<std::string> defines;
    switch (settings.method) {
        case AoMethod::Ssao:
            defines.emplace_back("AO_SSAO");
            break;
        case AoMethod::Hbao:
            defines.emplace_back("AO_HBAO");
            break;
        case AoMethod::Gtao:
        case AoMethod::None:
            defines.emplace_back("AO_GTAO");
            break;
        case AoMethod::Traced:  // ao_traced.frag: the noise's alone
            break;
    }
    if (usesBackLayer(settings)) defines.emplace_back("SECOND_LAYER");
    switch (settings.noise) {
        case AoNoise::White:
            defines.emplace_back("NOISE_WHITE");
            break;
        case AoNoise::InterleavedGradient:
            defines.emplace_back("NOISE_IGN");
            break;
        case AoNoise::Blue:
            defines.emplace_back("NOISE_BLUE");
            break;
    }
    return defines;
}

gl::Texture runAmbientOcclusionPass(ProgramCache& programs, const gl::Texture& surface,
                                    const gl::Texture& normalUv, const AoSettings& settings,
                                    double radius, const gl::Texture* back,
                                    const OcclusionGridBuffers* grid) {
    const int w = surface.width(), h = surface.height();
    gl::Texture open[2] = {gl::Texture(w, h, gl::Format::R32F),
                           gl::Texture(w, h, gl::Format::R32F)};
    gl::Framebuffer targets[2] = {gl::Framebuffer("ao", {{&open[0]}}),
                                  gl::Framebuffer("ao blur", {{&open[1]}})};
    gl::setPipelineState({});
    surface.bind(2);

    const gl::Program& estimate =
        settings.method == AoMethod::Traced
            ? tracedOcclusionProgram(programs, settings, *grid)
            : programs.get("fullscreen.vert", "ao.frag", ambientOcclusionDefines(settings));
    estimate.use();
    estimate.set("uRadius", static_cast<float>(radius));
    estimate.set("uSlices", settings.slices);
    estimate.set("uSteps", settings.steps);
    estimate.set("uMaxPixels", static_cast<float>(settings.maxPixels));
    estimate.set("uAngleBias",
                 static_cast<float>(settings.angleBiasDeg * 3.14159265358979 / 180.0));
    estimate.set("uGtaoBias",
                 static_cast<float>(settings.gtaoAngleBiasDeg * 3.14159265358979 / 180.0));
    estimate.set("uThickness", static_cast<float>(settings.thickness));
    estimate.set("uDepth", 0.0f);
    normalUv.bind(0);
    if (back) back->bind(6);
    // 16 KB uploaded with the frame: no texture outlives the frame's GL context.
    gl::Texture noise;
    if (settings.noise == AoNoise::Blue) {
        noise = gl::Texture(BLUE_NOISE_SIDE, BLUE_NOISE_SIDE, gl::Format::R32F);
        noise.upload(blueNoiseTile());
        noise.bind(5);
    }
    targets[0].bind();
    gl::drawFullscreenTriangle();
    if (settings.blur == AoBlur::None || radius <= 0.0) return std::move(open[0]);

    std::vector<std::string> defines;
    if (settings.blur == AoBlur::DepthAware) defines.emplace_back("AO_DEPTH_AWARE");
    const gl::Program& blur = programs.get("fullscreen.vert", "ao_blur.frag", defines);
    blurSeparably(blur, settings.blurRadius, open, targets);
    return std::move(open[0]);
}

std::vector<std::string> backLayerDefines(DepthMode mode) {
    return {depthDefine(mode), "BACK_LAYER"};
}

gl::Texture runBackLayerPass(ProgramCache& programs, const SceneBuffers& scene,
                             const gl::Texture& surface, DepthMode mode) {
    const int w = surface.width(), h = surface.height();
    gl::Texture back(w, h, gl::Format::R32F);
    // The farthest far side wins: the depth test reversed against the G-buffer's.
    gl::Texture depth(w, h,
                      mode == DepthMode::Standard ? gl::Format::Depth24 : gl::Format::Depth32F);
    gl::Framebuffer target("ao back layer", {{&back}}, gl::Attachment{&depth});
    target.bind();
    target.clearColor(0, glm::vec4(0.0f));
    const bool reversed = mode == DepthMode::Reversed;
    target.clearDepth(reversed ? 1.0f : 0.0f);
    gl::setPipelineState(
        {.depthTest = reversed ? gl::DepthTest::Less : gl::DepthTest::Greater,
         .depthWrite = true,
         .depthClamp = true,
         .clipDepth = reversed ? gl::ClipDepth::ZeroToOne : gl::ClipDepth::MinusOneToOne});
    surface.bind(6);
    scene.drawImpostors(programs, "gbuffer.frag", backLayerDefines(mode));
    gl::setPipelineState({});
    return back;
}

}  // namespace twinrender::realtime
