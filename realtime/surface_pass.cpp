// The "surface" pass: a depth filter (shaders/bilateral.frag, narrow_range.frag,
// curvature_flow.frag) ping-ponging the G-buffer's surface (eye depth, body, radius, material),
// then the normals rebuilt from the filtered depth (depth_normals.frag); or the user's shader
// (user_surface.frag around realtime.surface.shader). Every pixel is drawn, the background
// copied, so the frame's depth and normal channels read the result everywhere.
#include <fmt/format.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "realtime/gl/error.h"
#include "realtime/gl/pipeline.h"
#include "realtime/passes.h"

namespace twinrender::realtime {

namespace {

constexpr int NORMAL_UV_UNIT = 0, EMISSION_UNIT = 1, SURFACE_UNIT = 2;

// The narrow-range filter's final 2-D pass in its separable schedule (the authors' demo).
constexpr float NARROW_RANGE_FINAL_RADIUS_PX = 4.0f;

IncludedFile userFile(const SurfaceSettings& s) {
    return {"user_surface.glsl", s.shaderPath, s.shaderSource};
}

// Draws `program` over the whole target.
void drawAll(const gl::Program& program, const gl::Framebuffer& target) {
    program.use();
    program.set("uDepth", 0.0f);
    target.bind();
    gl::drawFullscreenTriangle();
}

// Ping-pong textures of one format and size, each with a framebuffer of its own.
struct PingPong {
    std::array<gl::Texture, 2> textures;
    std::array<std::optional<gl::Framebuffer>, 2> targets;
    int next = 0;

    PingPong(const char* name, int w, int h) {
        for (int i = 0; i < 2; ++i) {
            textures[i] = gl::Texture(w, h, gl::Format::RGBA32F);
            targets[i].emplace(fmt::format("{} {}", name, i),
                               std::vector<gl::Attachment>{{&textures[i]}});
        }
    }
    // Draws into the next texture and returns it.
    const gl::Texture& draw(const gl::Program& program) {
        drawAll(program, *targets[next]);
        const gl::Texture& written = textures[next];
        next = 1 - next;
        return written;
    }
};

// The depth filter's steps over the surface: each reads the last one's result at unit 2.
class DepthFilter {
  public:
    DepthFilter(const GBuffer& g, int w, int h)
        : mSurfaces("surface", w, h), mCurrent(&g.surface) {}

    void step(const gl::Program& program) {
        mCurrent->bind(SURFACE_UNIT);
        mCurrent = &mSurfaces.draw(program);
    }
    const gl::Texture& current() const { return *mCurrent; }
    // The filtered surface, or nothing when no step ran (the G-buffer's stands).
    std::optional<gl::Texture> take() {
        for (auto& t : mSurfaces.textures)
            if (&t == mCurrent) return std::move(t);
        return std::nullopt;
    }

  private:
    PingPong mSurfaces;
    const gl::Texture* mCurrent;
};

void runBilateral(ProgramCache& programs, const BilateralSettings& b, DepthFilter& f) {
    std::vector<std::string> defines;
    if (b.separable) defines.emplace_back("SEPARABLE");
    const gl::Program& program = programs.get("fullscreen.vert", "bilateral.frag", defines);
    program.set("uRadius", static_cast<float>(b.radius));
    program.set("uDepthSigma", static_cast<float>(b.depthSigma));
    program.set("uMaxRadiusPx", static_cast<float>(b.maxRadiusPx));
    for (int i = 0; i < b.iterations; ++i) {
        if (b.separable) {
            program.set("uDirection", glm::vec2(1.0f, 0.0f));
            f.step(program);
            program.set("uDirection", glm::vec2(0.0f, 1.0f));
            f.step(program);
        } else {
            f.step(program);
        }
    }
}

void runNarrowRange(ProgramCache& programs, const NarrowRangeSettings& n, DepthFilter& f) {
    auto setUp = [&](const gl::Program& p) {
        p.set("uRadius", static_cast<float>(n.radius));
        p.set("uThreshold", static_cast<float>(n.threshold));
        p.set("uClamp", static_cast<float>(n.clamp));
        p.set("uMaxRadiusPx", static_cast<float>(n.maxRadiusPx));
        p.set("uFixedRadiusPx", 0.0f);
    };
    const gl::Program& full = programs.get("fullscreen.vert", "narrow_range.frag");
    setUp(full);
    if (!n.separable) {
        for (int i = 0; i < n.iterations; ++i) f.step(full);
        return;
    }
    const gl::Program& line = programs.get("fullscreen.vert", "narrow_range.frag", {"SEPARABLE"});
    setUp(line);
    for (int i = 0; i + 1 < n.iterations; ++i) {
        line.set("uDirection", glm::vec2(1.0f, 0.0f));
        f.step(line);
        line.set("uDirection", glm::vec2(0.0f, 1.0f));
        f.step(line);
    }
    full.set("uFixedRadiusPx", NARROW_RANGE_FINAL_RADIUS_PX);
    f.step(full);
}

void runCurvatureFlow(ProgramCache& programs, const CurvatureFlowSettings& c, DepthFilter& f) {
    const gl::Program& program = programs.get("fullscreen.vert", "curvature_flow.frag");
    program.set("uTimeStep", static_cast<float>(c.timeStep));
    program.set("uDepthLimit", static_cast<float>(c.depthLimit));
    for (int i = 0; i < c.iterations; ++i) f.step(program);
}

// Normals rebuilt from `surface`'s depth, uv from `normalUv`.
gl::Texture depthNormals(ProgramCache& programs, const gl::Texture& surface,
                         const gl::Texture& normalUv) {
    gl::Texture out(surface.width(), surface.height(), gl::Format::RGBA32F);
    gl::Framebuffer target("depth normals", {{&out}});
    normalUv.bind(NORMAL_UV_UNIT);
    surface.bind(SURFACE_UNIT);
    drawAll(programs.get("fullscreen.vert", "depth_normals.frag"), target);
    return out;
}

FilteredSurface runUserShader(ProgramCache& programs, const GBuffer& g, const gl::Texture& normalUv,
                              const SurfaceSettings& s) {
    const int w = g.surface.width(), h = g.surface.height();
    const gl::Program& program = userSurfaceProgram(programs, s);
    struct Targets {
        gl::Texture surface, normalUv, emission;
    };
    std::array<Targets, 2> targets;
    std::array<std::optional<gl::Framebuffer>, 2> framebuffers;
    for (int i = 0; i < 2; ++i) {
        for (gl::Texture* t : {&targets[i].surface, &targets[i].normalUv, &targets[i].emission})
            *t = gl::Texture(w, h, gl::Format::RGBA32F);
        framebuffers[i].emplace(
            fmt::format("user surface {}", i),
            std::vector<gl::Attachment>{
                {&targets[i].surface}, {&targets[i].normalUv}, {&targets[i].emission}});
    }
    const gl::Texture *surface = &g.surface, *normals = &normalUv, *emission = &g.emission;
    int current = 0;
    for (int i = 0; i < s.shaderPasses; ++i) {
        current = i % 2;
        normals->bind(NORMAL_UV_UNIT);
        emission->bind(EMISSION_UNIT);
        surface->bind(SURFACE_UNIT);
        drawAll(program, *framebuffers[current]);
        surface = &targets[current].surface;
        normals = &targets[current].normalUv;
        emission = &targets[current].emission;
    }
    FilteredSurface result;
    result.surface = std::move(targets[current].surface);
    result.emission = std::move(targets[current].emission);
    result.normalUv = s.shaderNormals
                          ? depthNormals(programs, *result.surface, targets[current].normalUv)
                          : std::move(targets[current].normalUv);
    return result;
}

}  // namespace

const gl::Program& userSurfaceProgram(ProgramCache& programs, const SurfaceSettings& s) {
    const IncludedFile user = userFile(s);
    try {
        return programs.get("fullscreen.vert", "user_surface.frag", {}, &user);
    } catch (const gl::Error& e) {
        throw core::InputError(
            fmt::format("{}: realtime.surface.shader does not compile; the compiler says:\n{}",
                        s.shaderPath, e.what()));
    }
}

void compileSurfacePrograms(ProgramCache& programs, const SurfaceSettings& s) {
    switch (s.method) {
        case SurfaceMethod::Bilateral:
            programs.get("fullscreen.vert", "bilateral.frag",
                         s.bilateral.separable ? std::vector<std::string>{"SEPARABLE"}
                                               : std::vector<std::string>{});
            break;
        case SurfaceMethod::NarrowRange:
            programs.get("fullscreen.vert", "narrow_range.frag");
            if (s.narrowRange.separable)
                programs.get("fullscreen.vert", "narrow_range.frag", {"SEPARABLE"});
            break;
        case SurfaceMethod::CurvatureFlow:
            programs.get("fullscreen.vert", "curvature_flow.frag");
            break;
        case SurfaceMethod::Shader:
            userSurfaceProgram(programs, s);
            break;
        case SurfaceMethod::Ssss:
        case SurfaceMethod::None:
            return;
    }
    if (s.method != SurfaceMethod::Shader || s.shaderNormals)
        programs.get("fullscreen.vert", "depth_normals.frag");
}

FilteredSurface runSurfacePass(ProgramCache& programs, const GBuffer& g,
                               const gl::Texture& normalUv, const SurfaceSettings& s) {
    gl::setPipelineState({});
    if (s.method == SurfaceMethod::Shader) return runUserShader(programs, g, normalUv, s);
    DepthFilter filter(g, g.surface.width(), g.surface.height());
    if (s.method == SurfaceMethod::Bilateral) runBilateral(programs, s.bilateral, filter);
    if (s.method == SurfaceMethod::NarrowRange) runNarrowRange(programs, s.narrowRange, filter);
    if (s.method == SurfaceMethod::CurvatureFlow)
        runCurvatureFlow(programs, s.curvatureFlow, filter);
    FilteredSurface result;
    result.normalUv = depthNormals(programs, filter.current(), normalUv);
    result.surface = filter.take();
    return result;
}

}  // namespace twinrender::realtime
