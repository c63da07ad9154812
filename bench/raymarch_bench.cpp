// The reference raymarcher's speed on OpenSPH's own benchmark view of ball.ssf (issue:
// "OpenSPH's raymarcher takes 0.46 s per pass on these 2 cores"): the full render with
// shadows, the same rays against plain spheres (the cost floor), and the Embree queries the
// implicit surface is built on. Run: build/bench/raymarch_bench [--benchmark_repetitions=5]
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <ctime>

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

}  // namespace

BENCHMARK(BM_BallImplicitShadows)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BallImplicitNoShadows)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BallSpheresShadows)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BallClosestHitPerPixel)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BallGatherPerHitPixel)
    ->Arg(0)
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
