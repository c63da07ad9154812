// The real-time renderer's per-stage cost (issue 3, "Speed"): the planet scene at 1280 x 720
// with 100k particles, all defaults (log depth, 2048^2 shadow map, separable SSSS, bloom),
// and variants that switch one feature off. Counters are milliseconds per stage from the GL
// timer queries (cull, upload, readback and total are wall clock), averaged over iterations.
// The target: ssss + shade + post <= (gbuffer + shadow) / 2, total < 1000 ms on the
// 2-core llvmpipe machines; 1M particles at 1920 x 1080 under 5 ms on a GPU.
// Each iteration is one frame of a frame loop over an unchanged particle set: the culling
// answer and the field normals are computed once (in the warm-up render) and the previous
// frame is handed back (Renderer::recycle). BM_Planet100k720pFirstFrame is a new device and
// renderer per frame: culling and field normals included, compile excluded.
// BM_Planet100k720pSurface/<method>: each surface method at its defaults.
// BM_Planet*NewSet/<gpu|cpu>: every frame a new particle set (the particles move by a few
// float ulps between frames, so the per-set work is redone: counters.per_set_builds = 1), with
// realtime.per_set = gpu or cpu; per_set_ms is the sum of the per-set stages (grid,
// particle_normals, radius, droplets, kernels, cull, field_normals, anisotropy, upload, pack) and
// per_set_share its share of the frame. BM_Planet1M1080pNewSet/gpu is the GPU target (a
// frame of a new 1M-particle set at 1920 x 1080 under 16 ms): it runs as it is on an NVIDIA EGL
// device. BM_PerSet1MGpu: the per-set stages alone (realtime/per_set_gpu.h, no render passes) for a
// new 1M-particle set every iteration: a quick measure of those stages while working on them.
// The per-set benchmarks report their first run, on fresh buffers, beside the steady runs
// (fresh_per_set_ms; fresh_drawn or fresh_particles_drawn against drawn or particles_drawn).
// Run:
// build/bench/realtime_bench [--benchmark_filter=...] [--benchmark_repetitions=3]
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/vec3.hpp>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/install_layout.h"
#include "core/particles.h"
#include "core/scene.h"
#include "core/texture.h"
#include "realtime/gl/context.h"
#include "realtime/impostor_radius.h"
#include "realtime/occlusion_culling.h"
#include "realtime/per_set_gpu.h"
#include "realtime/renderer.h"
#include "realtime/settings.h"

namespace tr = twinrender;

namespace {

struct LoadedScene {
    tr::core::Scene scene;
    tr::core::SceneParticles particles;
    std::vector<tr::core::Material> materials;
    tr::realtime::Settings settings;
};

// The planet scene with that many particles at that size; `more`: further overrides.
const LoadedScene& planet(int particles, int width, int height,
                          const std::vector<std::string>& more = {}) {
    static std::map<std::string, std::unique_ptr<LoadedScene>> cache;
    std::string key = fmt::format("{}@{}x{}", particles, width, height);
    for (const std::string& m : more) key += " " + m;
    auto& slot = cache[key];
    if (!slot) {
        slot = std::make_unique<LoadedScene>();
        std::vector<std::string> overrides = {fmt::format("bodies.0.particles={}", particles),
                                              fmt::format("camera.width={}", width),
                                              fmt::format("camera.height={}", height)};
        overrides.insert(overrides.end(), more.begin(), more.end());
        slot->scene = tr::core::loadScene((::twinrender::core::sourceDir() / "scenes/planet.toml"),
                                          overrides);
        slot->settings = tr::realtime::parseSettings(slot->scene.realtime);
        slot->particles = tr::core::buildParticles(slot->scene);
        slot->materials = tr::core::loadMaterials(slot->scene);
    }
    return *slot;
}

tr::realtime::gl::Context& context() {
    static tr::realtime::gl::Context c;
    return c;
}

// Milliseconds per stage, averaged over the iterations, and frame_ms: the frame without the
// read-back of the AOVs (total - readback), which the GPU targets exclude (timed apart).
void addStageCounters(benchmark::State& state, const std::map<std::string, double>& sums) {
    for (const auto& [stage, ms] : sums)
        if (stage != "compile")
            state.counters[fmt::format("{}_ms", stage)] =
                benchmark::Counter(ms, benchmark::Counter::kAvgIterations);
    const auto total = sums.find("total"), readback = sums.find("readback");
    if (total != sums.end())
        state.counters["frame_ms"] =
            benchmark::Counter(total->second - (readback != sums.end() ? readback->second : 0.0),
                               benchmark::Counter::kAvgIterations);
    state.SetLabel(context().renderer());
}

void frame(benchmark::State& state, int particles, int width, int height,
           void (*adjust)(tr::realtime::Settings&), const std::vector<std::string>& more = {}) {
    const LoadedScene& s = planet(particles, width, height, more);
    tr::realtime::Settings settings = s.settings;
    if (adjust) adjust(settings);
    tr::realtime::Device device(context());
    tr::realtime::Renderer renderer(device, settings);
    const tr::core::RenderInput input{s.scene, s.particles, s.materials};
    // Compiles the programs; culling and field normals are computed once per particle set.
    renderer.recycle(renderer.render(input));
    std::map<std::string, double> sums;
    for (auto _ : state) {
        tr::core::Frame r = renderer.render(input);
        for (const auto& [stage, ms] : r.timingsMs) sums[stage] += ms;
        benchmark::DoNotOptimize(r.image.pixels().data());
        renderer.recycle(std::move(r));  // a frame loop hands its frames back
    }
    addStageCounters(state, sums);
}

void BM_Planet100k720pFirstFrame(benchmark::State& state) {
    const LoadedScene& s = planet(100000, 1280, 720);
    std::map<std::string, double> sums;
    for (auto _ : state) {
        tr::realtime::Device device(context());  // nothing compiled or culled yet
        tr::realtime::Renderer renderer(device, s.settings);
        const tr::core::Frame r = renderer.render({s.scene, s.particles, s.materials});
        for (const auto& [stage, ms] : r.timingsMs) sums[stage] += ms;
        benchmark::DoNotOptimize(r.image.pixels().data());
    }
    for (const auto& [stage, ms] : sums)
        if (stage != "compile")
            state.counters[fmt::format("{}_ms", stage)] =
                benchmark::Counter(ms, benchmark::Counter::kAvgIterations);
    state.SetLabel(context().renderer());
}

void BM_Planet100k720p(benchmark::State& state) {
    frame(state, 100000, 1280, 720, nullptr);
}
void BM_Planet100k720pNoSsss(benchmark::State& state) {
    frame(state, 100000, 1280, 720, [](tr::realtime::Settings& s) { s.ssss.enabled = false; });
}
void BM_Planet100k720pNoCulling(benchmark::State& state) {
    frame(state, 100000, 1280, 720,
          [](tr::realtime::Settings& s) { s.particles.cullHidden = false; });
}
void BM_Planet100k720pFull2dSsss(benchmark::State& state) {
    frame(state, 100000, 1280, 720, [](tr::realtime::Settings& s) { s.ssss.separable = false; });
}
// Each surface method at its defaults (realtime.surface.method; docs/methods.md): the
// "ssss" or "surface" counter is the method's pass, "normals" the gradient pass before it.
void BM_Planet100k720pSurface(benchmark::State& state, tr::realtime::SurfaceMethod method) {
    static tr::realtime::SurfaceMethod chosen;
    chosen = method;
    frame(state, 100000, 1280, 720, [](tr::realtime::Settings& s) {
        s.surface.method = chosen;
        if (chosen == tr::realtime::SurfaceMethod::Shader) {
            s.surface.shaderPath = "surface_pass_through.glsl";
            s.surface.shaderSource = "void filterSurface(ivec2 p, inout SurfaceSample s) {}\n";
        }
    });
}
// Ellipsoid particles (realtime.particles.shape; never culled) with the default surface method.
void BM_Planet100k720pEllipsoids(benchmark::State& state) {
    frame(state, 100000, 1280, 720, [](tr::realtime::Settings& s) {
        s.particles.shape = tr::realtime::ParticleShape::Ellipsoid;
    });
}
// A distant glowing planet (blackbody glow at 3000 K), 100k particles 25 px across at 720p:
// its surface particles are 0.5 px in radius, drawn as impostors (most cover no pixel centre),
// as flux splats (particles.min_pixels = 1) or with halos (particles.halo_pixels = 2). The
// "gbuffer" counter is the impostors' pass, "halo" the halos'.
void BM_DistantGlowingPlanet100k720p(benchmark::State& state, double minPixels, double halo) {
    static double chosenMin, chosenHalo;
    chosenMin = minPixels;
    chosenHalo = halo;
    frame(state, 100000, 1280, 720,
          [](tr::realtime::Settings& s) {
              s.particles.minPixels = chosenMin;
              s.particles.haloPixels = chosenHalo;
          },
          {"camera.position=[0.0, -88.0, 25.0]", "bodies.0.temperature=3000"});
}

// The GPU target of the issue (slow on llvmpipe: run it where a GPU is present).
void BM_Planet1M1080p(benchmark::State& state) {
    frame(state, 1000000, 1920, 1080, nullptr);
}

// Every frame a new particle set: the per-set work redone each frame (per_set = gpu or cpu).
void newSetFrames(benchmark::State& state, int particles, int width, int height,
                  tr::realtime::PerSetDevice where) {
    const LoadedScene& s = planet(particles, width, height);
    tr::realtime::Settings settings = s.settings;
    settings.perSet = where;
    tr::realtime::Device device(context());
    tr::realtime::Renderer renderer(device, settings);
    // Two sets that differ in every position by one float ulp: alternating them, each frame's
    // set differs from the last, and the images are the same.
    tr::core::SceneParticles sets[2] = {s.particles, s.particles};
    for (glm::vec3& p : sets[1].particles.position)
        p = glm::vec3(std::nextafter(p.x, 1e30f), p.y, p.z);
    auto perSetMs = [](const tr::core::Frame& r) {
        double ms = 0.0;
        for (const char* stage : {"grid", "particle_normals", "radius", "droplets", "kernels",
                                  "cull", "field_normals", "anisotropy", "upload", "pack"}) {
            const auto it = r.timingsMs.find(stage);
            ms += it == r.timingsMs.end() ? 0.0 : it->second;
        }
        return ms;
    };
    // The first frame on fresh buffers (compile included in its "compile" stage, not here),
    // reported beside the steady frames: a driver fault that shows on new buffers only shows as
    // fresh_particles_drawn apart from particles_drawn.
    tr::core::Frame fresh = renderer.render({s.scene, sets[1], s.materials});
    state.counters["fresh_per_set_ms"] = perSetMs(fresh);
    state.counters["fresh_particles_drawn"] = fresh.counters["particles_drawn"];
    renderer.recycle(std::move(fresh));
    std::map<std::string, double> sums;
    double builds = 0.0, perSet = 0.0, drawn = 0.0;
    int frame = 0;
    for (auto _ : state) {
        tr::core::Frame r = renderer.render({s.scene, sets[frame++ % 2], s.materials});
        for (const auto& [stage, ms] : r.timingsMs) sums[stage] += ms;
        perSet += perSetMs(r);
        builds += r.counters["per_set_builds"];
        drawn = r.counters["particles_drawn"];
        benchmark::DoNotOptimize(r.image.pixels().data());
        renderer.recycle(std::move(r));
    }
    addStageCounters(state, sums);
    state.counters["particles_drawn"] = drawn;
    state.counters["per_set_ms"] = benchmark::Counter(perSet, benchmark::Counter::kAvgIterations);
    state.counters["per_set_share"] = perSet / std::max(sums["total"], 1e-9);
    state.counters["per_set_builds"] =
        benchmark::Counter(builds, benchmark::Counter::kAvgIterations);
}

void BM_Planet100k720pNewSet(benchmark::State& state, tr::realtime::PerSetDevice where) {
    newSetFrames(state, 100000, 1280, 720, where);
}
void BM_Planet1M1080pNewSet(benchmark::State& state, tr::realtime::PerSetDevice where) {
    newSetFrames(state, 1000000, 1920, 1080, where);
}

// The per-set work alone on the GPU (realtime/per_set_gpu.h), without the render passes: every
// iteration a new set (as newSetFrames), what the planet's frame asks for (its radii,
// culling), each stage in milliseconds and per_set_ms their sum.
void BM_PerSet1MGpu(benchmark::State& state) {
    const LoadedScene& s = planet(1000000, 1920, 1080);
    tr::realtime::PerSetRequest request;
    request.particles = s.settings.particles;
    request.cull = s.settings.particles.cullHidden;
    request.droplets = s.settings.particles.radius == tr::realtime::RadiusModel::Field &&
                       s.settings.particles.dropletAtoms >= 2;
    tr::core::SceneParticles sets[2] = {s.particles, s.particles};
    for (glm::vec3& p : sets[1].particles.position)
        p = glm::vec3(std::nextafter(p.x, 1e30f), p.y, p.z);
    context().makeCurrent();
    tr::realtime::ProgramCache programs;
    tr::realtime::compilePerSetPrograms(programs, request);
    tr::realtime::GpuPerSet perSet;
    const tr::realtime::FrameRequest frame{s.scene.camera.position, 1e-3};
    // The first run, on fresh buffers, reported beside the steady runs on kept ones: a driver
    // fault that shows on new buffers only shows as fresh_drawn apart from drawn.
    perSet.update(programs, sets[1].particles, request, sets[1].bodies);
    perSet.pack(programs, frame);
    double fresh = perSet.uploadMs();
    for (const auto& [stage, ms] : perSet.takeTimings()) fresh += ms;
    state.counters["fresh_per_set_ms"] = fresh;
    state.counters["fresh_drawn"] = double(perSet.drawnCount());
    std::map<std::string, double> sums;
    int k = 0;
    for (auto _ : state) {
        const tr::core::SceneParticles& set = sets[k++ % 2];
        perSet.update(programs, set.particles, request, set.bodies);
        perSet.pack(programs, frame);
        sums["upload"] += perSet.uploadMs();
        for (const auto& [stage, ms] : perSet.takeTimings()) sums[stage] += ms;
    }
    double total = 0.0;
    for (const auto& [stage, ms] : sums) {
        state.counters[fmt::format("{}_ms", stage)] =
            benchmark::Counter(ms, benchmark::Counter::kAvgIterations);
        total += ms;
    }
    state.counters["per_set_ms"] = benchmark::Counter(total, benchmark::Counter::kAvgIterations);
    state.counters["drawn"] = double(perSet.drawnCount());
    state.SetLabel(context().renderer());
}

// Occlusion culling alone (CPU, part of "upload").
void BM_Cull100k(benchmark::State& state) {
    const LoadedScene& s = planet(100000, 1280, 720);
    std::size_t kept = 0;
    for (auto _ : state)
        kept = tr::realtime::unoccludedParticles(
                   s.particles.particles, tr::realtime::fixedRadii(s.particles.particles, 0.9))
                   .size();
    state.counters["kept"] = double(kept);
}

// The four GPU targets of realtime/README.md ("On a GPU"), by name: frame_ms (the frame
// without the read-back) of a steady 1M-particle frame at 1920 x 1080, of a frame of a new 1M
// set there, of a steady planet 100k at 1280 x 720; and readback_ms, the read-back of every
// AOV at 1920 x 1080. Run: realtime_bench --benchmark_filter='^Target/'
// --benchmark_repetitions=3 --benchmark_report_aggregates_only=true (scripts/gpu-check).
void targetSteady1M(benchmark::State& state) {
    frame(state, 1000000, 1920, 1080, nullptr);
}
void targetNewSet1M(benchmark::State& state) {
    newSetFrames(state, 1000000, 1920, 1080, tr::realtime::PerSetDevice::Gpu);
}
void targetPlanet100k(benchmark::State& state) {
    frame(state, 100000, 1280, 720, nullptr);
}
void targetReadback1080p(benchmark::State& state) {
    frame(state, 100000, 1920, 1080, nullptr);
}
[[maybe_unused]] const bool TARGETS_REGISTERED = [] {
    for (const auto& [name, function] : {std::pair{"Target/steady_1M_1080p", &targetSteady1M},
                                         {"Target/new_set_1M_1080p", &targetNewSet1M},
                                         {"Target/planet_100k_720p_steady", &targetPlanet100k},
                                         {"Target/readback_aovs_1080p", &targetReadback1080p}})
        benchmark::RegisterBenchmark(name, function)->Unit(benchmark::kMillisecond)->Iterations(5);
    return true;
}();

}  // namespace

BENCHMARK(BM_Planet100k720p)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Planet100k720pFirstFrame)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_Planet100k720pNoSsss)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Planet100k720pFull2dSsss)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(BM_Planet100k720pSurface, none, tr::realtime::SurfaceMethod::None)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_Planet100k720pSurface, ssss, tr::realtime::SurfaceMethod::Ssss)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_Planet100k720pSurface, bilateral, tr::realtime::SurfaceMethod::Bilateral)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_Planet100k720pSurface, narrow_range, tr::realtime::SurfaceMethod::NarrowRange)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_Planet100k720pSurface, curvature_flow,
                  tr::realtime::SurfaceMethod::CurvatureFlow)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_Planet100k720pSurface, shader_pass_through,
                  tr::realtime::SurfaceMethod::Shader)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK(BM_Planet100k720pEllipsoids)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Planet100k720pNoCulling)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_PerSet1MGpu)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Cull100k)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Planet1M1080p)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(BM_DistantGlowingPlanet100k720p, impostors, 0.0, 0.0)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_DistantGlowingPlanet100k720p, min_pixels_1, 1.0, 0.0)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_DistantGlowingPlanet100k720p, halo_2, 0.0, 2.0)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_Planet100k720pNewSet, gpu, tr::realtime::PerSetDevice::Gpu)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_Planet100k720pNewSet, cpu, tr::realtime::PerSetDevice::Cpu)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_Planet1M1080pNewSet, gpu, tr::realtime::PerSetDevice::Gpu)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_Planet1M1080pNewSet, cpu, tr::realtime::PerSetDevice::Cpu)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

BENCHMARK_MAIN();
