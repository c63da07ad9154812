// The whole-body sphere (realtime.particles.body_sphere_pixels) on llvmpipe: a ball of
// particles drawn as its one level-set sphere covers what its particles cover, its silhouette
// and depth are the analytic sphere's in every depth encoding, and a body larger on screen
// than the threshold is drawn as its particles, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <numbers>

#include "core/body_sphere.h"
#include "core/camera.h"
#include "core/derived_attributes.h"
#include "realtime/body_sphere_lod.h"
#include "realtime/testing/gl_test_scene.h"

namespace twinrender::realtime {
namespace {

using testing::Channels;
using testing::RendererTest;
using testing::TestScene;

// A cubic-lattice ball of radius 1 (spacing 0.1, h = 0.13: 4169 particles) at the origin, its
// normals radial and its uv the generated particles' (core::sphericalUv), seen from 5 away: its
// level set about 37 pixels in radius on the 160 x 90 image.
TestScene ball() {
    TestScene t;
    t.scene.camera.position = {0.0, 0.0, 5.0};
    t.scene.camera.up = {0.0, 1.0, 0.0};
    core::BodyInfo body{.name = "ball", .material = 0};
    for (int z = -10; z <= 10; ++z)
        for (int y = -10; y <= 10; ++y)
            for (int x = -10; x <= 10; ++x) {
                if (x * x + y * y + z * z > 100) continue;
                const glm::vec3 p = glm::vec3(x, y, z) * 0.1f;
                const core::SphericalUv s =
                    core::sphericalUv(glm::dvec3(p), body.center, body.frame);
                t.add(0, p, 0.13f, glm::vec2(s.uv),
                      glm::normalize(glm::vec3(x, y, z) + glm::vec3(0.0f, 0.0f, 0.01f)));
            }
    body.end = t.particles.particles.size();
    t.particles.bodies[0] = body;
    return t;
}

// The ball's level-set sphere at the renderer's default surface level.
core::BodySphere ballSphere(const TestScene& t) {
    const std::vector<core::BodySphere> spheres = core::bodySpheres(t.particles, 0.13);
    EXPECT_EQ(spheres.size(), 1u);
    return spheres.at(0);
}

Settings cpuSettings(double bodySpherePixels, DepthMode depth = DepthMode::Log) {
    Settings s = testing::quiet();
    s.perSet = PerSetDevice::Cpu;
    s.particles.radius = RadiusModel::Field;  // the default radii: the particles' own level set
    s.particles.bodySpherePixels = bodySpherePixels;
    s.depth = depth;
    return s;
}

// The eye ray through pixel (x, y)'s centre against the sphere: its closest approach to the
// centre, and the hit's eye depth (the ray's distance along the view axis).
struct RayHit {
    double miss = 0.0;
    double depth = 0.0;
};
RayHit traceSphere(const core::Camera& camera, int x, int y, const glm::dvec3& centre,
                   double radius) {
    const core::Ray ray = camera.ray(x + 0.5, y + 0.5);
    const glm::dvec3 o = centre - ray.origin;
    const double along = glm::dot(o, ray.direction);
    RayHit h;
    h.miss = glm::length(o - along * ray.direction);
    if (h.miss < radius) {
        const double t = along - std::sqrt(radius * radius - h.miss * h.miss);
        h.depth = t * glm::dot(ray.direction, camera.forward());
    }
    return h;
}

TEST_F(RendererTest, TheWholeBodySphereCoversWhatItsParticlesCover) {
    TestScene t = ball();
    t.finish();
    const core::Frame particles = render(t, cpuSettings(0.0));
    const core::Frame sphere = render(t, cpuSettings(4096.0));
    EXPECT_EQ(particles.counters.at("body_spheres"), 0.0);
    EXPECT_EQ(sphere.counters.at("body_spheres"), 1.0);
    EXPECT_EQ(sphere.counters.at("particles_drawn"), 0.0);
    const Channels a{particles.image}, b{sphere.image};
    int both = 0, either = 0;
    for (int y = 0; y < testing::HEIGHT; ++y)
        for (int x = 0; x < testing::WIDTH; ++x) {
            const bool pa = a(x, y, "id") >= 0.0f, pb = b(x, y, "id") >= 0.0f;
            both += pa && pb;
            either += pa || pb;
        }
    const double iou = double(both) / either;
    std::printf("coverage IoU sphere / particles: %.4f (%d of %d pixels)\n", iou, both, either);
    // The particles' outline is scalloped by a tenth of the radius (one spacing, 3.7 px)
    // around the level set whose mean radius the sphere takes: the pixels in the scallops
    // differ, 2.4 % of the disc's 4400 on llvmpipe; 0.95 leaves room for another rasteriser.
    EXPECT_GT(iou, 0.95);
    EXPECT_GT(either, 3000);
}

TEST_F(RendererTest, TheWholeBodySphereIsTheAnalyticSphereInEveryDepthEncoding) {
    TestScene t = ball();
    t.finish();
    const core::BodySphere s = ballSphere(t);
    // The level set of a lattice ball of radius 1 (h 0.13) lies about 0.9 h beyond it.
    EXPECT_NEAR(s.radius, 1.0 + 0.9 * 0.13, 0.05);
    const core::Camera camera(t.scene.camera);
    for (DepthMode depth : {DepthMode::Log, DepthMode::Reversed, DepthMode::Standard}) {
        const core::Frame f = render(t, cpuSettings(4096.0, depth));
        const Channels c{f.image};
        int covered = 0, near = 0;
        for (int y = 0; y < testing::HEIGHT; ++y)
            for (int x = 0; x < testing::WIDTH; ++x) {
                const RayHit h = traceSphere(camera, x, y, s.centre, s.radius);
                // The shader's intersection is in 32-bit floats from a float radius: a ray
                // within 1e-4 of the radius (a 300th of a pixel) may fall either side.
                if (std::abs(h.miss - s.radius) < 1e-4 * s.radius) {
                    ++near;
                    continue;
                }
                const bool hit = h.miss < s.radius;
                ASSERT_EQ(c(x, y, "id") >= 0.0f, hit) << toString(depth) << " " << x << " " << y;
                if (!hit) continue;
                ++covered;
                EXPECT_EQ(c(x, y, "id"), 0.0f);
                // Eye depth from the float ray-sphere hit: relative error of a few ulps of the
                // 5-unit distance, more at grazing rays where the root's slope is steep.
                EXPECT_NEAR(c(x, y, "Z"), h.depth, 2e-4 * h.depth + 1e-3 * (h.miss / s.radius))
                    << toString(depth) << " " << x << " " << y;
                // The analytic normal and the generated particles' uv at the hit point.
                const core::Ray ray = camera.ray(x + 0.5, y + 0.5);
                const glm::dvec3 p =
                    ray.origin +
                    ray.direction * (h.depth / glm::dot(ray.direction, camera.forward()));
                const glm::dvec3 n = glm::normalize(p - s.centre);
                const glm::dvec3 got(c(x, y, "N.X"), c(x, y, "N.Y"), c(x, y, "N.Z"));
                EXPECT_GT(glm::dot(glm::normalize(got), n),
                          std::cos(0.5 * std::numbers::pi / 180.0))
                    << x << " " << y;
                const core::SphericalUv uv = core::sphericalUv(p, glm::dvec3(0.0), glm::dmat3(1.0));
                const double du = std::abs(c(x, y, "uv.U") - uv.uv.x);
                EXPECT_LT(std::min(du, 1.0 - du), 2e-3) << x << " " << y;
                EXPECT_NEAR(c(x, y, "uv.V"), uv.uv.y, 2e-3) << x << " " << y;
            }
        EXPECT_GT(covered, 3000);
        EXPECT_LT(near, 10);
    }
}

// At 37 pixels the ball is above a threshold of 30 and below one of 40.
TEST_F(RendererTest, ABodyLargerThanTheThresholdIsDrawnAsItsParticles) {
    TestScene t = ball();
    t.finish();
    const core::BodySphere s = ballSphere(t);
    const double px = projectedRadiusPixels(core::Camera(t.scene.camera), s.centre, s.radius);
    ASSERT_GT(px, 30.0);
    ASSERT_LT(px, 40.0);
    const core::Frame off = render(t, cpuSettings(0.0));
    const core::Frame above = render(t, cpuSettings(30.0));
    const core::Frame below = render(t, cpuSettings(40.0));
    EXPECT_EQ(above.counters.at("body_spheres"), 0.0);
    EXPECT_EQ(below.counters.at("body_spheres"), 1.0);
    auto same = [](const core::Image& a, const core::Image& b) {
        return a.pixels().size() == b.pixels().size() &&
               std::memcmp(a.pixels().data(), b.pixels().data(),
                           a.pixels().size() * sizeof(float)) == 0;
    };
    EXPECT_TRUE(same(off.image, above.image));
    EXPECT_FALSE(same(off.image, below.image));
}

// A droplet of two sparse particles (body 1, a few pixels across) beside the ball (37 px): at
// a threshold of 10 px the droplet becomes its body's sphere and the ball is drawn as before,
// pixel for pixel.
TEST_F(RendererTest, AReplacedBodyLeavesTheOtherBodiesDrawn) {
    TestScene t = ball();
    const std::size_t first = t.add(1, {1.8f, 0.5f, 0.0f}, 0.13f);
    t.add(1, {1.95f, 0.5f, 0.0f}, 0.13f);
    t.particles.bodies[1] = {.name = "pair", .begin = first, .end = first + 2};
    t.finish();
    const core::Frame off = render(t, cpuSettings(0.0));
    const core::Frame on = render(t, cpuSettings(10.0));
    EXPECT_EQ(on.counters.at("body_spheres"), 1.0);
    EXPECT_GE(off.counters.at("droplets"), 1.0);
    EXPECT_EQ(on.counters.at("droplets"), off.counters.at("droplets") - 1.0);
    const Channels a{off.image}, b{on.image};
    int ball = 0, pair = 0;
    for (int y = 0; y < testing::HEIGHT; ++y)
        for (int x = 0; x < testing::WIDTH; ++x) {
            pair += b(x, y, "id") == 1.0f;
            if (a(x, y, "id") != 0.0f) continue;
            ++ball;
            EXPECT_EQ(b(x, y, "id"), 0.0f) << x << " " << y;
            EXPECT_EQ(b(x, y, "Z"), a(x, y, "Z")) << x << " " << y;
        }
    EXPECT_GT(ball, 3000);
    EXPECT_GT(pair, 0);
}

}  // namespace
}  // namespace twinrender::realtime
