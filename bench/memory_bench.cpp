// Resident memory over a long frame loop (issue 13, "Reliability"): each renderer renders
// FRAMES frames (default 1000) of a small planet (2,000 particles at 64 x 48, a 256^2 shadow
// map) with a new particle set every frame (the particles moved, so every per-particle-set
// answer is computed anew: culling, impostor radii, field normals, the raymarcher's BVH), and
// prints the growth of the process's resident memory (VmRSS, /proc/self/status) per frame
// after a warm-up. A renderer that keeps something per particle set, or leaks per frame, shows
// as a steady growth; allocator noise is a few KiB in all.
// Run: build/bench/memory_bench [FRAMES] [realtime|raymarch|both]
#include <fmt/format.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "core/install_layout.h"
#include "core/particles.h"
#include "core/renderer.h"
#include "core/scene.h"
#include "core/texture.h"
#include "raymarch/embree_device.h"
#include "raymarch/renderer.h"
#include "raymarch/settings.h"
#include "realtime/gl/context.h"
#include "realtime/renderer.h"
#include "realtime/settings.h"

namespace tr = twinrender;

namespace {

constexpr int WARM_UP_FRAMES = 50;

// The process's resident set, KiB.
long residentKib() {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::strtol(line.c_str() + 6, nullptr, 10);
    return -1;
}

struct Scene {
    tr::core::Scene scene;
    tr::core::SceneParticles particles;
    std::vector<tr::core::Material> materials;
};

Scene smallPlanet() {
    Scene s;
    const std::vector<std::string> overrides = {"bodies.0.particles=2000", "camera.width=64",
                                                "camera.height=48",
                                                "realtime.shadow_map.resolution=256"};
    s.scene =
        tr::core::loadScene((::twinrender::core::sourceDir() / "scenes/planet.toml"), overrides);
    s.particles = tr::core::buildParticles(s.scene);
    s.materials = tr::core::loadMaterials(s.scene);
    return s;
}

// Frame `f`'s particle set: the first one moved by a small wobble (a new set every frame;
// the same shape, so every frame costs alike).
void moveTo(const tr::core::SceneParticles& first, int f, tr::core::SceneParticles& moved) {
    const glm::vec3 offset(0.01f * std::sin(0.1f * float(f)), 0.01f * std::cos(0.13f * float(f)),
                           0.0f);
    for (std::size_t i = 0; i < first.particles.position.size(); ++i)
        moved.particles.position[i] = first.particles.position[i] + offset;
    moved.boundsMin = first.boundsMin + glm::dvec3(offset);
    moved.boundsMax = first.boundsMax + glm::dvec3(offset);
}

void loop(const char* name, tr::core::Renderer& renderer, const Scene& s, int frames) {
    tr::core::SceneParticles moved = s.particles;
    long warm = 0, peak = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int f = 0; f < frames; ++f) {
        moveTo(s.particles, f, moved);
        renderer.recycle(renderer.render({s.scene, moved, s.materials}));
        if (f + 1 == WARM_UP_FRAMES) warm = residentKib();
        if (f + 1 >= WARM_UP_FRAMES) peak = std::max(peak, residentKib());
    }
    const long end = residentKib();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const int measured = frames - WARM_UP_FRAMES;
    std::printf(
        "%-8s %d frames of %zu particles at %dx%d, a new particle set each (%.1f ms a frame): "
        "VmRSS %.1f MiB after %d warm-up frames, %.1f MiB after %d (peak %.1f MiB): "
        "%+.2f KiB per frame\n",
        name, frames, s.particles.particles.position.size(), s.scene.camera.width,
        s.scene.camera.height, 1000.0 * seconds / frames, warm / 1024.0, WARM_UP_FRAMES,
        end / 1024.0, frames, peak / 1024.0, measured > 0 ? double(end - warm) / measured : 0.0);
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
    const int frames = argc > 1 ? std::atoi(argv[1]) : 1000;
    const std::string which = argc > 2 ? argv[2] : "both";
    if (frames <= WARM_UP_FRAMES ||
        (which != "both" && which != "realtime" && which != "raymarch")) {
        std::fprintf(stderr, "usage: memory_bench [FRAMES > %d] [realtime|raymarch|both]\n",
                     WARM_UP_FRAMES);
        return 4;
    }
    const Scene s = smallPlanet();
    if (which != "raymarch") {
        tr::realtime::gl::Context context;
        tr::realtime::Device device(context);
        tr::realtime::Renderer renderer(device, tr::realtime::parseSettings(s.scene.realtime));
        loop("realtime", renderer, s, frames);
    }
    if (which != "realtime") {
        tr::raymarch::EmbreeDevice device;
        tr::raymarch::Renderer renderer(device, tr::raymarch::parseSettings(s.scene.raymarch));
        loop("raymarch", renderer, s, frames);
    }
    return 0;
}
