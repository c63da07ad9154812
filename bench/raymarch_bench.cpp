// The reference raymarcher's speed on OpenSPH's own benchmark view of ball.ssf (issue:
// "OpenSPH's raymarcher takes 0.46 s per pass on these 2 cores"): the full render with
// shadows, the same rays against plain spheres (the cost floor), and the Embree queries the
// implicit surface is built on. Then each kind of secondary ray on its study scene, at the
// fixed count and with a standard-error target. Run:
// build/bench/raymarch_bench [--benchmark_repetitions=5]
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <ctime>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/install_layout.h"
#include "core/sph_kernel.h"
#include "raymarch/renderer.h"
#include "raymarch/sphere_scene.h"

namespace tr = twinrender;

namespace {

// CPU time of the whole process (every thread), in ms: steadier than wall time on a machine
// that other jobs share.
double processCpuMs() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

struct BallScene {
    tr::core::Scene scene;
    std::vector<tr::core::Material> materials;
    tr::core::SceneParticles particles;
    tr::raymarch::Settings settings;
    explicit BallScene(std::vector<std::string> overrides = {}) {
        scene = tr::core::loadScene((::twinrender::core::sourceDir() / "scenes/opensph_ball.toml"),
                                    overrides);
        settings = tr::raymarch::parseSettings(scene.raymarch);
        materials = tr::core::loadMaterials(scene);
        particles = tr::core::buildParticles(scene);
    }
};

const BallScene& ball() {
    static const BallScene s;
    return s;
}

void renderBall(benchmark::State& state, bool spheres, bool shadows) {
    const BallScene& s = ball();
    tr::raymarch::Settings settings = s.settings;
    settings.spheres = spheres;
    settings.shadows = shadows;
    tr::raymarch::EmbreeDevice device;
    double unresolved = 0;
    const double cpuStart = processCpuMs();
    tr::raymarch::Renderer renderer(device, settings);
    for (auto _ : state) {
        tr::core::Frame frame = renderer.render({s.scene, s.particles, s.materials});
        unresolved = frame.counters["unbracketed_rays"];
        benchmark::DoNotOptimize(frame.image.pixels().data());
    }
    state.counters["unbracketed"] = unresolved;
    state.counters["process_cpu_ms"] = (processCpuMs() - cpuStart) / double(state.iterations());
}

void BM_BallImplicitShadows(benchmark::State& state) {
    renderBall(state, false, true);
}
void BM_BallImplicitNoShadows(benchmark::State& state) {
    renderBall(state, false, false);
}
void BM_BallSpheresShadows(benchmark::State& state) {
    renderBall(state, true, true);
}

// The exact surface's cost over the plain spheres' on the same rays (ball.ssf at 800x600 with
// shadows): both rendered each iteration, alternately, in the process's CPU time (every
// thread), so that the machine's load falls on both alike.
void BM_BallImplicitOverSpheres(benchmark::State& state) {
    const BallScene& s = ball();
    tr::raymarch::EmbreeDevice device;
    double implicitMs = 0.0, spheresMs = 0.0;
    for (auto _ : state)
        for (const bool spheres : {false, true}) {
            tr::raymarch::Settings settings = s.settings;
            settings.spheres = spheres;
            settings.shadows = true;
            tr::raymarch::Renderer renderer(device, settings);
            const double start = processCpuMs();
            tr::core::Frame frame = renderer.render({s.scene, s.particles, s.materials});
            benchmark::DoNotOptimize(frame.image.pixels().data());
            (spheres ? spheresMs : implicitMs) += processCpuMs() - start;
        }
    const double n = double(state.iterations());
    state.counters["implicit_cpu_ms"] = implicitMs / n;
    state.counters["spheres_cpu_ms"] = spheresMs / n;
    state.counters["implicit_over_spheres"] = implicitMs / spheresMs;
}

// The particles' support spheres (radius 2h, where the M4 kernel ends).
tr::raymarch::SphereScene supportSpheres(tr::raymarch::EmbreeDevice& device,
                                         const tr::core::ParticleSet& ps) {
    std::vector<float> radii(ps.size());
    for (std::size_t i = 0; i < ps.size(); ++i) radii[i] = 2.0f * ps.h[i];
    return tr::raymarch::SphereScene(device, ps.position, radii);
}

// Embree alone: one closest-hit query per pixel against the support spheres.
void BM_BallClosestHitPerPixel(benchmark::State& state) {
    const BallScene& s = ball();
    tr::raymarch::EmbreeDevice device;
    tr::raymarch::SphereScene spheres = supportSpheres(device, s.particles.particles);
    tr::core::Camera camera(s.scene.camera);
    std::int64_t hits = 0;
    for (auto _ : state) {
        hits = 0;
        for (int y = 0; y < camera.height(); ++y)
            for (int x = 0; x < camera.width(); ++x) {
                const auto ray = camera.ray(x + 0.5, y + 0.5);
                tr::raymarch::SphereScene::Hit h;
                hits += spheres.closestHit(glm::vec3(ray.origin), glm::vec3(ray.direction), 0.0f,
                                           1e30f, h);
            }
    }
    state.counters["hits"] = double(hits);
}

// Embree alone: gather every support sphere along 4h after the first entry, per hit pixel.
void BM_BallGatherPerHitPixel(benchmark::State& state) {
    const BallScene& s = ball();
    tr::raymarch::EmbreeDevice device;
    tr::raymarch::SphereScene spheres = supportSpheres(device, s.particles.particles);
    tr::core::Camera camera(s.scene.camera);
    std::vector<std::uint32_t> prims;
    const float length = static_cast<float>(state.range(0)) * 0.25f;  // in units of h
    std::int64_t gathered = 0, rays = 0;
    std::vector<std::pair<glm::vec3, glm::vec3>> segs;
    for (int y = 0; y < camera.height(); ++y)
        for (int x = 0; x < camera.width(); ++x) {
            const auto ray = camera.ray(x + 0.5, y + 0.5);
            tr::raymarch::SphereScene::Hit h;
            if (spheres.closestHit(glm::vec3(ray.origin), glm::vec3(ray.direction), 0.0f, 1e30f, h))
                segs.push_back({glm::vec3(ray.origin + double(h.t) * ray.direction),
                                glm::vec3(ray.direction)});
        }
    const float hMean = static_cast<float>(s.particles.bodies[0].meanH);
    for (auto _ : state) {
        gathered = 0;
        for (const auto& [o, d] : segs) {
            prims.clear();
            spheres.gather(o, d, 0.0f, length * hMean, prims);
            gathered += prims.size();
        }
        rays = segs.size();
    }
    state.counters["rays"] = double(rays);
    state.counters["hits_per_ray"] = double(gathered) / double(rays);
    state.counters["ns_per_hit"] =
        benchmark::Counter(double(gathered), benchmark::Counter::kIsIterationInvariantRate |
                                                 benchmark::Counter::kInvert);
}

// CPU time of the calling thread, in ms.
double threadCpuMs() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

// One kind of secondary ray on its study scene (tests/scenes/), rendered on one thread (the
// calling one, whose CPU time is steadier than wall time on a shared machine) and split among
// the stages as the frame's times are: the primary pass (stage "trace": the camera rays, and
// a point sun's shadow rays where the scene has one) and the kind's stage, their rays per
// second, the kind's CPU cost per ray over the primary pass's per pixel, and the rays, mean
// and largest standard error the frame states for the kind. The
// fixed count is 64 directions; `target` > 0 sets the kind's raymarch.*_error.
void renderSecondary(benchmark::State& state, const std::string& scene, const std::string& kind,
                     const std::string& stage, const std::string& key, double target) {
    const std::vector<std::string> sets = {"raymarch." + key + "_samples=64",
                                           "raymarch." + key + "_error=" + std::to_string(target)};
    const tr::core::Scene s =
        tr::core::loadScene(tr::core::sourceDir() / "tests" / "scenes" / (scene + ".toml"), sets);
    const tr::raymarch::Settings settings = tr::raymarch::parseSettings(s.raymarch);
    const std::vector<tr::core::Material> materials = tr::core::loadMaterials(s);
    const tr::core::SceneParticles particles = tr::core::buildParticles(s);
    tr::raymarch::EmbreeDevice device;
    tr::raymarch::Renderer renderer(device, settings);
    tbb::task_arena arena(1);
    tr::core::Frame frame;
    double primaryMs = 0.0, stageMs = 0.0;
    for (auto _ : state) {
        const double start = threadCpuMs();
        arena.execute([&] { frame = renderer.render({s, particles, materials}); });
        const double cpuPerWallMs = (threadCpuMs() - start) / frame.timingsMs.at("total");
        primaryMs += frame.timingsMs.at("trace") * cpuPerWallMs;
        stageMs += frame.timingsMs.at(stage) * cpuPerWallMs;
        benchmark::DoNotOptimize(frame.image.pixels().data());
    }
    const double n = double(state.iterations());
    state.counters["primary_ms"] = primaryMs / n;
    state.counters["primary_Mrays_s"] = frame.counters.at("primary_rays") / (primaryMs / n) / 1e3;
    state.counters["kind_ms"] = stageMs / n;
    state.counters["kind_rays"] = frame.counters.at(kind + "_rays");
    state.counters["kind_Mrays_s"] = frame.counters.at(kind + "_rays") / (stageMs / n) / 1e3;
    // The kind's cost per ray over the primary pass's per pixel (the targets are ratios:
    // both scale alike with the machine and its load).
    const double pixels = double(s.camera.width) * double(s.camera.height);
    state.counters["ray_per_pixel_cost"] =
        (stageMs / frame.counters.at(kind + "_rays")) / (primaryMs / pixels);
    state.counters["se_mean"] = frame.counters.at(kind + "_standard_error");
    state.counters["se_max"] = frame.counters.at(kind + "_standard_error_max");
}

}  // namespace

// Per kind, the fixed count and two targets: the first takes about a third of the fixed
// count's rays on the study scene, the second is about as far from a converged reference
// (docs/performance.md, "Secondary rays in rounds").
BENCHMARK_CAPTURE(renderSecondary, occlusion_fixed64, "ball_on_slab", "ao", "ao", "ao", 0.0)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(renderSecondary, occlusion_error_0_05, "ball_on_slab", "ao", "ao", "ao", 0.05)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(renderSecondary, occlusion_error_0_03, "ball_on_slab", "ao", "ao", "ao", 0.03)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(renderSecondary, emissive_fixed64, "lamp_over_slab", "irradiance", "emissive",
                  "emissive", 0.0)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(renderSecondary, emissive_error_0_2, "lamp_over_slab", "irradiance", "emissive",
                  "emissive", 0.2)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(renderSecondary, emissive_error_0_1, "lamp_over_slab", "irradiance", "emissive",
                  "emissive", 0.1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(renderSecondary, sun_fixed64, "ring_shadow", "sun", "sun", "sun", 0.0)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(renderSecondary, sun_error_0_05, "ring_shadow", "sun", "sun", "sun", 0.05)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(renderSecondary, sun_error_0_02, "ring_shadow", "sun", "sun", "sun", 0.02)
    ->Unit(benchmark::kMillisecond);

BENCHMARK(BM_BallImplicitShadows)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BallImplicitNoShadows)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BallSpheresShadows)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BallImplicitOverSpheres)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BallClosestHitPerPixel)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BallGatherPerHitPixel)
    ->Arg(0)
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
