// Post (shaders/bloom_*.frag, shaders/composite.frag): bloom as a chain of half-size levels
// (bright pass, downsample, tent upsample with additive blending), then the tonemapper. The
// result is the PNG's image only; the EXR keeps the linear beauty without bloom.
#include <algorithm>

#include "realtime/gl/pipeline.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

namespace {
constexpr int MAX_BLOOM_LEVELS = 6;
constexpr int MIN_BLOOM_SIZE = 4;  // pixels: no level smaller than this
}  // namespace

gl::Texture runPostPass(ProgramCache& programs, const gl::Texture& beauty,
                        const BloomSettings& bloom, float exposure) {
    const int w = beauty.width(), h = beauty.height();
    std::vector<gl::Texture> levels;
    std::vector<gl::Framebuffer> levelTargets;
    if (bloom.enabled && bloom.strength > 0.0) {
        for (int lw = w / 2, lh = h / 2;
             lw >= MIN_BLOOM_SIZE && lh >= MIN_BLOOM_SIZE && int(levels.size()) < MAX_BLOOM_LEVELS;
             lw /= 2, lh /= 2)
            levels.emplace_back(lw, lh, gl::Format::RGBA32F, gl::Filter::Linear);
        for (std::size_t i = 0; i < levels.size(); ++i)
            levelTargets.emplace_back("bloom " + std::to_string(i),
                                      std::vector<gl::Attachment>{{&levels[i]}});
    }
    gl::setPipelineState({});
    if (!levels.empty()) {
        const gl::Program& bright = programs.get("fullscreen.vert", "bloom_bright.frag");
        bright.use();
        bright.set("uThreshold", static_cast<float>(bloom.threshold));
        beauty.bind(0);
        levelTargets[0].bind();
        gl::drawFullscreenTriangle();
        const gl::Program& down = programs.get("fullscreen.vert", "bloom_down.frag");
        down.use();
        for (std::size_t i = 1; i < levels.size(); ++i) {
            levels[i - 1].bind(0);
            levelTargets[i].bind();
            gl::drawFullscreenTriangle();
        }
        const gl::Program& up = programs.get("fullscreen.vert", "bloom_up.frag");
        up.use();
        gl::setPipelineState({.additiveBlend = true});
        for (std::size_t i = levels.size() - 1; i > 0; --i) {
            levels[i].bind(0);
            up.set("uTargetTexel",
                   glm::vec2(1.0f / levels[i - 1].width(), 1.0f / levels[i - 1].height()));
            levelTargets[i - 1].bind();
            gl::drawFullscreenTriangle();
        }
        gl::setPipelineState({});
    }

    gl::Texture display(w, h, gl::Format::RGBA32F);
    gl::Framebuffer target("post", {{&display}});
    target.bind();
    const gl::Program& composite = programs.get(
        "fullscreen.vert", "composite.frag",
        levels.empty() ? std::vector<std::string>{} : std::vector<std::string>{"BLOOM"});
    composite.use();
    composite.set("uExposure", exposure);
    // Each level adds its own copy of the bright pass: divide by their number so that the
    // strength is the bloom's share of the bright radiance.
    composite.set("uStrength",
                  levels.empty() ? 0.0f : static_cast<float>(bloom.strength / levels.size()));
    beauty.bind(0);
    if (!levels.empty()) levels[0].bind(1);
    gl::drawFullscreenTriangle();
    return display;
}

}  // namespace twinrender::realtime
