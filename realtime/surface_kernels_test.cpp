#include "realtime/surface_kernels.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/sph_kernel.h"

namespace twinrender::realtime {
namespace {

// A cube of n^3 lattice particles (spacing s, h = 1.3 s, normals pointing out of the cube).
core::ParticleSet cube(int n, float s) {
    core::ParticleSet ps;
    const float c = 0.5f * (n - 1);
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec3 d(x - c, y - c, z - c);
                ps.position.push_back(d * s);
                ps.h.push_back(1.3f * s);
                ps.volume.push_back(s * s * s);
                ps.normal.push_back(glm::length(d) > 0 ? glm::normalize(d) : glm::vec3(0, 0, 1));
            }
    ps.body.assign(ps.position.size(), 0);
    return ps;
}

// In a 15^3 cube the level set lies about 0.92 h (1.2 spacings) beyond the outer layer: the two
// outer layers' supports (2 h = 2.6 spacings) reach it and stay; layers from the fourth in,
// whose probes at 2.5 h (3.25 spacings) all stay inside, are left out; a lone particle stays.
TEST(SurfaceKernels, DeepParticlesAreLeftOutSurfaceOnesKept) {
    const int n = 15;
    const float s = 0.1f;
    core::ParticleSet ps = cube(n, s);
    const std::vector<std::uint32_t> kept = surfaceKernels(ps, 0.13);
    auto isKept = [&](int x, int y, int z) {
        return std::binary_search(kept.begin(), kept.end(),
                                  static_cast<std::uint32_t>((z * n + y) * n + x));
    };
    for (int layer = 0; layer < 2; ++layer) EXPECT_TRUE(isKept(layer, n / 2, n / 2)) << layer;
    for (int layer = 3; layer <= n / 2; ++layer) EXPECT_FALSE(isKept(layer, n / 2, n / 2)) << layer;
    EXPECT_LT(kept.size(), ps.size() * 3 / 4);
    EXPECT_GT(kept.size(), ps.size() / 3);
    // A lone particle far away: its support is mostly outside.
    ps.position.push_back({100.0f, 0.0f, 0.0f});
    ps.h.push_back(0.13f);
    ps.volume.push_back(0.001f);
    ps.normal.push_back({0.0f, 0.0f, 1.0f});
    ps.body.push_back(1);
    const std::vector<std::uint32_t> withLone = surfaceKernels(ps, 0.13);
    EXPECT_EQ(withLone.back(), ps.size() - 1);
}

TEST(SurfaceKernels, TheCacheReusesItsAnswerOnlyForTheSameInputs) {
    core::ParticleSet ps = cube(6, 0.1f);
    SurfaceKernelCache cache;
    const std::vector<std::uint32_t> first = cache.kernels(ps, 0.13);
    EXPECT_FALSE(cache.reused());
    EXPECT_EQ(cache.kernels(ps, 0.13), first);
    EXPECT_TRUE(cache.reused());
    cache.kernels(ps, 0.2);
    EXPECT_FALSE(cache.reused());
    ps.position[0].x += 0.01f;
    cache.kernels(ps, 0.2);
    EXPECT_FALSE(cache.reused());
}

}  // namespace
}  // namespace twinrender::realtime
