#include "realtime/error_split.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "core/camera.h"
#include "core/error.h"
#include "realtime/gl/pipeline.h"
#include "realtime/octahedral.h"

namespace twinrender::realtime {

ExactPlanes exactPlanes(const core::Image& aov, const core::RenderInput& in,
                        const Settings& settings) {
    const int w = in.scene.camera.width, h = in.scene.camera.height;
    if (aov.width() != w || aov.height() != h)
        throw core::NotComparableError(
            fmt::format("error split: the reference is {}x{} pixels but the camera {}x{}",
                        aov.width(), aov.height(), w, h));
    const auto channel = [&](const char* name) {
        const int c = aov.channelIndex(name);
        if (c < 0)
            throw core::NotComparableError(
                fmt::format("error split: the reference image has no channel \"{}\"", name));
        return c;
    };
    const int cA = channel("A"), cZ = channel("Z"), cN = channel("N.X"), cU = channel("uv.U"),
              cId = channel("id"), cE = channel("emission.R"), cShadow = channel("shadow");
    const int cAo = aov.channelIndex("ao");  // frames written before it: open everywhere
    const int cIrradiance = aov.channelIndex("irradiance.R");  // before it: none
    const core::Camera camera(in.scene.camera);
    const double pixelsPerUnit = 0.5 * h / camera.tanHalfFovY();  // times 1 / depth
    const std::size_t n = static_cast<std::size_t>(w) * h * 4;
    ExactPlanes p{std::vector<float>(n, 0.0f), std::vector<float>(n, 0.0f),
                  std::vector<float>(n, 0.0f), std::vector<float>(n, 0.0f),
                  std::vector<float>(n, 0.0f)};
    const auto& bodies = in.particles.bodies;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // GL rows run bottom-up; images top-down.
            const std::size_t g = (static_cast<std::size_t>(h - 1 - y) * w + x) * 4;
            const float z = aov.at(x, y, cZ), id = aov.at(x, y, cId);
            if (!(aov.at(x, y, cA) > 0.0f) || !std::isfinite(z) || id < 0.0f) {
                p.surface[g] = std::numeric_limits<float>::infinity();
                p.surface[g + 1] = -1.0f;
                continue;
            }
            const std::size_t body = static_cast<std::size_t>(id);
            const double meanH = body < bodies.size() ? bodies[body].meanH : 0.0;
            p.surface[g] = z;
            p.surface[g + 1] = id;
            p.surface[g + 2] =
                static_cast<float>(meanH * settings.particles.radiusScale * pixelsPerUnit / z);
            p.surface[g + 3] =
                body < bodies.size() ? static_cast<float>(bodies[body].material) : 0.0f;
            const glm::vec3 normal(aov.at(x, y, cN), aov.at(x, y, cN + 1), aov.at(x, y, cN + 2));
            const float length = glm::length(normal);
            const glm::vec2 e = octEncode(length > 0.0f ? normal / length : glm::vec3(0, 0, 1));
            p.normalUv[g] = e.x;
            p.normalUv[g + 1] = e.y;
            p.normalUv[g + 2] = aov.at(x, y, cU);
            p.normalUv[g + 3] = aov.at(x, y, cU + 1);
            for (int k = 0; k < 3; ++k) p.emission[g + k] = aov.at(x, y, cE + k);
            p.light[g] = aov.at(x, y, cShadow);
            p.light[g + 1] = cAo >= 0 ? aov.at(x, y, cAo) : 1.0f;
            if (cIrradiance >= 0)
                for (int k = 0; k < 3; ++k) p.irradiance[g + k] = aov.at(x, y, cIrradiance + k);
        }
    return p;
}

namespace {

// One channel of an RGBA plane.
std::vector<float> channelOf(const std::vector<float>& rgba, int c) {
    std::vector<float> out(rgba.size() / 4);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = rgba[i * 4 + c];
    return out;
}

gl::Texture uploaded(int w, int h, gl::Format format, const std::vector<float>& values) {
    gl::Texture t(w, h, format);
    t.upload(values);
    return t;
}

}  // namespace

ExactSurface uploadExactSurface(ProgramCache& programs, const core::Image& aov,
                                const core::RenderInput& in, const Settings& settings) {
    const ExactPlanes p = exactPlanes(aov, in, settings);
    const int w = in.scene.camera.width, h = in.scene.camera.height;
    const DepthMode mode = settings.depth;
    ExactSurface e{
        .gbuffer = {.normalUv = uploaded(w, h, gl::Format::RGBA32F, p.normalUv),
                    .emission = uploaded(w, h, gl::Format::RGBA32F, p.emission),
                    .surface = uploaded(w, h, gl::Format::RGBA32F, p.surface),
                    .depth = gl::Texture(
                        w, h,
                        mode == DepthMode::Standard ? gl::Format::Depth24 : gl::Format::Depth32F),
                    .framebuffer = {}},
        .visibility = uploaded(w, h, gl::Format::R32F, channelOf(p.light, 0)),
        .ambientOcclusion = uploaded(w, h, gl::Format::R32F, channelOf(p.light, 1)),
        .irradiance = uploaded(w, h, gl::Format::RGBA32F, p.irradiance)};
    // The depth buffer: the window depth of each covered pixel, as the G-buffer pass leaves it.
    e.gbuffer.framebuffer = gl::Framebuffer("exact depth", {}, gl::Attachment{&e.gbuffer.depth});
    e.gbuffer.framebuffer.bind();
    const bool reversed = mode == DepthMode::Reversed;
    e.gbuffer.framebuffer.clearDepth(reversed ? 0.0f : 1.0f);
    gl::setPipelineState(
        {.depthTest = reversed ? gl::DepthTest::Greater : gl::DepthTest::Less,
         .depthWrite = true,
         .depthClamp = true,
         .clipDepth = reversed ? gl::ClipDepth::ZeroToOne : gl::ClipDepth::MinusOneToOne});
    const gl::Program& program =
        programs.get("fullscreen.vert", "exact_depth.frag", {depthDefine(mode)});
    program.use();
    program.set("uDepth", 0.0f);
    e.gbuffer.surface.bind(2);
    gl::drawFullscreenTriangle();
    gl::setPipelineState({});
    return e;
}

}  // namespace twinrender::realtime
