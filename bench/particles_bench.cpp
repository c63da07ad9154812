// The particle set's derived attributes (core/derived_attributes.h) on the planet scene: the
// work every new particle set (a sequence's frame) costs on the CPU before either renderer
// sees it. Each stage alone: uv (per body, closed form), normals (neighbour grids and the
// colour field's gradient at every particle) and glow (blackbody radiance per temperature).
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/derived_attributes.h"
#include "core/install_layout.h"
#include "core/particles.h"
#include "core/scene.h"

namespace tr = twinrender;

namespace {

const tr::core::SceneParticles& planet(int particles) {
    static std::map<int, std::unique_ptr<tr::core::SceneParticles>> cache;
    auto& slot = cache[particles];
    if (!slot) {
        const std::vector<std::string> overrides = {
            fmt::format("bodies.0.particles={}", particles)};
        const tr::core::Scene scene = tr::core::loadScene(
            (::twinrender::core::sourceDir() / "scenes/planet.toml"), overrides);
        slot = std::make_unique<tr::core::SceneParticles>(tr::core::buildParticles(scene));
    }
    return *slot;
}

void BM_DeriveUv(benchmark::State& state) {
    const auto& s = planet(static_cast<int>(state.range(0)));
    tr::core::ParticleSet set = s.particles;
    for (auto _ : state)
        for (const auto& body : s.bodies) tr::core::deriveUv(set, body, false);
    state.counters["particles"] = double(set.size());
}

void BM_DeriveNormals(benchmark::State& state) {
    const auto& s = planet(static_cast<int>(state.range(0)));
    tr::core::ParticleSet set = s.particles;
    for (auto _ : state) tr::core::deriveNormals(set, s.bodies);
    state.counters["particles"] = double(set.size());
}

void BM_DeriveGlow(benchmark::State& state) {
    const auto& s = planet(static_cast<int>(state.range(0)));
    tr::core::ParticleSet set = s.particles;
    for (auto _ : state) tr::core::deriveGlow(set);
    state.counters["particles"] = double(set.size());
}

}  // namespace

BENCHMARK(BM_DeriveUv)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DeriveNormals)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DeriveGlow)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
