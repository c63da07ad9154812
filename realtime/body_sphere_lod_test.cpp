#include "realtime/body_sphere_lod.h"

#include <gtest/gtest.h>

#include <cmath>

namespace twinrender::realtime {
namespace {

core::Camera camera() {
    core::CameraSettings c;
    c.position = {0.0, 0.0, 10.0};
    c.target = {0.0, 0.0, 0.0};
    c.up = {0.0, 1.0, 0.0};
    c.fovYDeg = 90.0;  // tan(45 degrees) = 1: f = height / 2
    c.width = 200;
    c.height = 100;
    return core::Camera(c);
}

TEST(BodySphereLod, ProjectsTheSilhouetteConeSeenStraightAhead) {
    // f r / sqrt(D^2 - r^2) with f = 50 px, D = 10, r = 6: 50 * 6 / 8.
    EXPECT_NEAR(projectedRadiusPixels(camera(), {0.0, 0.0, 0.0}, 6.0), 37.5, 1e-9);
    // Behind the eye, or holding it: never small.
    EXPECT_TRUE(std::isinf(projectedRadiusPixels(camera(), {0.0, 0.0, 20.0}, 1.0)));
    EXPECT_TRUE(std::isinf(projectedRadiusPixels(camera(), {0.0, 0.0, 9.5}, 1.0)));
}

TEST(BodySphereLod, ReplacesTheBodiesBelowTheThreshold) {
    const std::vector<core::BodySphere> spheres = {
        {.body = 0, .centre = {0.0, 0.0, 0.0}, .radius = 1.0, .reach = 1.2},    // 5 px
        {.body = 2, .centre = {0.0, 0.0, -90.0}, .radius = 1.0, .reach = 1.2},  // 0.5 px
        {.body = 3, .centre = {3.0, 0.0, 0.0}, .radius = 0.0, .reach = 0.5}};   // no level set
    const BodySphereChoice off = chooseBodySpheres(spheres, 4, camera(), 0.0);
    EXPECT_TRUE(off.drawn.empty());
    EXPECT_EQ(off.replaced, std::vector<bool>(4, false));
    const BodySphereChoice one = chooseBodySpheres(spheres, 4, camera(), 1.0);
    ASSERT_EQ(one.drawn.size(), 1u);
    EXPECT_EQ(one.drawn[0].body, 2u);
    EXPECT_EQ(one.replaced, (std::vector<bool>{false, false, true, false}));
    EXPECT_FALSE(one.touchesOthers);
    const BodySphereChoice both = chooseBodySpheres(spheres, 4, camera(), 10.0);
    EXPECT_EQ(both.drawn.size(), 2u);
    // Body 0 (replaced) and body 3 (kept) lie 3 apart, their reaches 1.2 and 0.5.
    EXPECT_FALSE(both.touchesOthers);
    std::vector<core::BodySphere> touching = spheres;
    touching[2].reach = 2.0;
    EXPECT_TRUE(chooseBodySpheres(touching, 4, camera(), 10.0).touchesOthers);
}

TEST(BodySphereLod, LeavesOutTheReplacedBodiesParticles) {
    const std::vector<std::uint32_t> body = {0, 0, 1, 1, 2};
    const std::vector<bool> replaced = {false, true, false};
    EXPECT_EQ(withoutReplaced({}, body, replaced), (std::vector<std::uint32_t>{0, 1, 4}));
    const std::vector<std::uint32_t> some = {1, 3, 4};
    EXPECT_EQ(withoutReplaced(some, body, replaced), (std::vector<std::uint32_t>{1, 4}));
}

}  // namespace
}  // namespace twinrender::realtime
