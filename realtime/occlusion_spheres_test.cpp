#include "realtime/occlusion_spheres.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace twinrender::realtime {
namespace {

TEST(OcclusionSpheres, OneSpherePerBodyOverFivePercent) {
    core::SceneParticles scene;
    scene.bodies.resize(3);
    core::ParticleSet& ps = scene.particles;
    auto add = [&](std::uint32_t body, glm::vec3 p, float v) {
        ps.position.push_back(p);
        ps.volume.push_back(v);
        ps.body.push_back(body);
    };
    // Body 0: 60 particles around (1, 0, 0); body 1: 39 around (0, 5, 0); body 2: 1 (1 %).
    for (int i = 0; i < 60; ++i) add(0, glm::vec3(1.0f + (i % 2 ? 0.5f : -0.5f), 0, 0), 0.1f);
    for (int i = 0; i < 39; ++i) add(1, glm::vec3(0, 5, 0), 0.2f);
    add(2, glm::vec3(9, 9, 9), 1.0f);
    const auto spheres = occlusionSpheres(scene);
    ASSERT_EQ(spheres.size(), 2u);
    EXPECT_EQ(spheres[0].body, 0u);
    EXPECT_NEAR(spheres[0].centre.x, 1.0, 1e-6);
    EXPECT_NEAR(spheres[0].radius, std::cbrt(3.0 * 6.0 / (4.0 * std::numbers::pi)), 1e-5);
    EXPECT_EQ(spheres[1].body, 1u);
    EXPECT_NEAR(spheres[1].centre.y, 5.0, 1e-6);
}

}  // namespace
}  // namespace twinrender::realtime
