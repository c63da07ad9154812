#include "core/body_sphere.h"

#include <gtest/gtest.h>

#include "core/sph_kernel.h"

namespace twinrender::core {
namespace {

// One particle per body: its level set is the sphere where v W(r, h) = level.
TEST(BodySphere, OneParticlesSphereIsItsKernelsLevelSet) {
    SceneParticles sp;
    ParticleSet& ps = sp.particles;
    ps.resize(2);
    ps.position = {{0.0f, 0.0f, 0.0f}, {5.0f, 0.0f, 0.0f}};
    ps.h = {1.0f, 0.5f};
    ps.volume = {1.0f, 0.1f};
    ps.body = {0, 1};
    ps.glow = {{1.0f, 2.0f, 3.0f}, {0.0f, 0.0f, 0.0f}};
    sp.bodies.resize(3);
    sp.bodies[0].begin = 0;
    sp.bodies[0].end = 1;
    sp.bodies[1].begin = 1;
    sp.bodies[1].end = 2;  // body 2: no particles, no sphere
    const double level = 0.13;
    const std::vector<BodySphere> spheres = bodySpheres(sp, level);
    ASSERT_EQ(spheres.size(), 2u);
    const BodySphere& a = spheres[0];
    EXPECT_EQ(a.body, 0u);
    EXPECT_NEAR(glm::length(a.centre), 0.0, 1e-12);
    EXPECT_NEAR(a.reach, 2.0, 1e-12);
    EXPECT_NEAR(1.0 * m4Kernel(a.radius, 1.0), level, 1e-4);
    EXPECT_EQ(a.glow, glm::vec3(1.0f, 2.0f, 3.0f));
    // A smaller kernel (peak 0.1 / pi h^3 = 0.25): its own radius.
    EXPECT_EQ(spheres[1].body, 1u);
    EXPECT_NEAR(0.1 * m4Kernel(spheres[1].radius, 0.5), level, 1e-4);
}

// A particle whose field barely reaches the level: its level set is smaller than a step of the
// inward walk (a quarter of h), and is still found.
TEST(BodySphere, ALevelSetSmallerThanAStepIsFound) {
    SceneParticles sp;
    ParticleSet& ps = sp.particles;
    ps.resize(1);
    ps.position = {{1.0f, 2.0f, 3.0f}};
    ps.h = {1.0f};
    ps.volume = {0.44f};  // peak 0.44 / pi = 0.140, just above the level
    ps.body = {0};
    ps.glow = {glm::vec3(0.0f)};
    sp.bodies.resize(1);
    sp.bodies[0].end = 1;
    const double level = 0.13;
    const std::vector<BodySphere> spheres = bodySpheres(sp, level);
    ASSERT_EQ(spheres.size(), 1u);
    EXPECT_GT(spheres[0].radius, 0.0);
    EXPECT_LT(spheres[0].radius, 0.25);
    EXPECT_NEAR(0.44 * m4Kernel(spheres[0].radius, 1.0), level, 1e-4);
    EXPECT_NEAR(levelSetRadius(ps, sp.bodies[0], level), spheres[0].radius, 1e-12);
}

}  // namespace
}  // namespace twinrender::core
