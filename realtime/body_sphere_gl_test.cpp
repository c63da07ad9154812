// The whole-body sphere (realtime.particles.body_sphere_pixels) on llvmpipe: a ball of
// particles drawn as its one level-set sphere covers what its particles cover, its silhouette
// and depth are the analytic sphere's in every depth encoding, a body larger on screen than the
// threshold is drawn as its particles, bit for bit, and the GPU's per-set path (a mask of the
// replaced bodies, per_set.cpp) draws and counts what the CPU's does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/geometric.hpp>
#include <numbers>
#include <string>

#include "core/body_sphere.h"
#include "core/camera.h"
#include "core/derived_attributes.h"
#include "realtime/body_sphere_lod.h"
#include "realtime/self_check.h"
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

// ---- per_set = "gpu" against "cpu" ----

// A ball of `radius` (cubic lattice, spacing 0.1, h 0.13, radial normals) about `centre` as
// body `body`.
void addBall(TestScene& t, std::uint32_t body, glm::vec3 centre, int radius) {
    const std::size_t first = t.particles.particles.size();
    for (int z = -radius; z <= radius; ++z)
        for (int y = -radius; y <= radius; ++y)
            for (int x = -radius; x <= radius; ++x)
                if (x * x + y * y + z * z <= radius * radius)
                    t.add(body, centre + glm::vec3(x, y, z) * 0.1f, 0.13f, {0.5f, 0.5f},
                          glm::normalize(glm::vec3(x, y, z) + glm::vec3(0.0f, 0.0f, 0.01f)));
    t.particles.bodies[body].begin = first;
    t.particles.bodies[body].end = t.particles.particles.size();
}

// ball() (body 0, 37 px on screen), a small ball of radius 0.3 (body 1, about 14 px) beside it
// at `smallCentre`, and with `pair` a droplet of two sparse particles (body 2, a few px).
TestScene ballsAndPair(glm::vec3 smallCentre, bool pair) {
    TestScene t = ball();
    addBall(t, 1, smallCentre, 3);
    if (pair) {
        const std::size_t first = t.add(2, {1.8f, 0.5f, 0.0f}, 0.13f);
        t.add(2, {1.95f, 0.5f, 0.0f}, 0.13f);
        t.particles.bodies[2] = {.name = "pair", .begin = first, .end = first + 2};
    }
    t.finish();
    return t;
}

// The default settings (field radii, culling, droplets, gradient normals, the shadow map, SSSS)
// without bloom.
Settings perSetSettings(PerSetDevice where, double bodySpherePixels) {
    Settings s;
    s.perSet = where;
    s.bloom.enabled = false;
    s.particles.bodySpherePixels = bodySpherePixels;
    return s;
}

// Pixels whose coverage or body differ, and covered pixels whose red differs by over 1e-2.
struct Apart {
    int covered = 0, differ = 0, shaded = 0;
};
Apart apart(const core::Image& g, const core::Image& c) {
    const int alpha = g.requireChannel("A"), id = g.requireChannel("id"),
              red = g.requireChannel("R");
    Apart d;
    for (int y = 0; y < g.height(); ++y)
        for (int x = 0; x < g.width(); ++x) {
            d.covered += c.at(x, y, alpha) > 0.5f;
            if (g.at(x, y, alpha) != c.at(x, y, alpha) || g.at(x, y, id) != c.at(x, y, id)) {
                ++d.differ;
                continue;
            }
            if (c.at(x, y, alpha) > 0.5f)
                d.shaded += !(std::abs(g.at(x, y, red) - c.at(x, y, red)) <= 1e-2f);
        }
    return d;
}

// The GPU's frame against the CPU's: the same spheres, particles and droplets drawn, and the
// same image within per_set_gpu_gl_test.cpp's tolerance for the two paths: each path's radii
// are within 3e-4 h of the other's and its normals float sums in another order (the CPU
// splats the surface's kernels, the GPU gathers every one), so a few outline pixels may change
// coverage and a few pixels their front particle or their shading (each at most 1 in 200 of
// the covered pixels).
void expectTheSameFrame(const core::Frame& gpu, const core::Frame& cpu, const char* what) {
    for (const char* counter : {"body_spheres", "particles_drawn", "droplets"})
        EXPECT_EQ(gpu.counters.at(counter), cpu.counters.at(counter)) << what << " " << counter;
    const Apart d = apart(gpu.image, cpu.image);
    std::printf(
        "%s: %g spheres, %g particles, %g droplets; of %d covered pixels %d apart, %d "
        "shaded apart\n",
        what, gpu.counters.at("body_spheres"), gpu.counters.at("particles_drawn"),
        gpu.counters.at("droplets"), d.covered, d.differ, d.shaded);
    EXPECT_GT(d.covered, 3000) << what;
    EXPECT_LE(d.differ, d.covered / 200) << what;
    EXPECT_LE(d.shaded, d.covered / 200) << what;
}

// The small ball (14 px) and the droplet below 20 px are drawn as their spheres, the ball
// (37 px) as its particles, culled (no replaced body's supports reach another's).
TEST_F(RendererTest, TheGpuPathDrawsTheBodySpheresAsTheCpuPathDoes) {
    TestScene t = ballsAndPair({-1.9f, 0.5f, 0.0f}, true);
    const core::Frame off = render(t, perSetSettings(PerSetDevice::Cpu, 0.0));
    const core::Frame cpu = render(t, perSetSettings(PerSetDevice::Cpu, 20.0));
    const core::Frame gpu = render(t, perSetSettings(PerSetDevice::Gpu, 20.0));
    EXPECT_EQ(cpu.counters.at("body_spheres"), 2.0);
    EXPECT_EQ(cpu.counters.at("droplets"), off.counters.at("droplets") - 1.0);
    // The ball alone, culled.
    EXPECT_LT(cpu.counters.at("particles_drawn"), 0.5 * 4169);
    expectTheSameFrame(gpu, cpu, "culled");
    // The sphere's own normal stands on both paths (their kernels neither splatted nor
    // gathered), so the small ball's pixels shade alike: with its kernels gathered the GPU's
    // would take the particles' bumpy gradient (the shading test above fails).
    const Channels g{gpu.image}, c{cpu.image};
    int small = 0;
    for (int y = 0; y < testing::HEIGHT; ++y)
        for (int x = 0; x < testing::WIDTH; ++x) {
            if (c(x, y, "id") != 1.0f || g(x, y, "id") != 1.0f) continue;
            ++small;
            const glm::vec3 a(g(x, y, "N.X"), g(x, y, "N.Y"), g(x, y, "N.Z"));
            const glm::vec3 b(c(x, y, "N.X"), c(x, y, "N.Y"), c(x, y, "N.Z"));
            EXPECT_GT(glm::dot(glm::normalize(a), glm::normalize(b)), 0.9999f) << x << " " << y;
        }
    EXPECT_GT(small, 300);
}

// The small ball glowing, with halos (particles.halo_pixels) for its particles, which are a
// few pixels each: drawn as its sphere, it has none on either path (the GPU's halo program
// drops the replaced body's particles as the impostor programs do).
TEST_F(RendererTest, TheGpuPathLeavesOutTheReplacedBodysHalosAsTheCpuPathDoes) {
    TestScene t = ballsAndPair({-1.9f, 0.5f, 0.0f}, true);
    const core::BodyInfo& small = t.particles.bodies[1];
    for (std::size_t i = small.begin; i < small.end; ++i)
        t.particles.particles.glow[i] = glm::vec3(2.0f, 1.0f, 0.5f);
    Settings gpu = perSetSettings(PerSetDevice::Gpu, 20.0), cpu = gpu;
    cpu.perSet = PerSetDevice::Cpu;
    gpu.particles.haloPixels = cpu.particles.haloPixels = 64.0;
    expectTheSameFrame(render(t, gpu), render(t, cpu), "halos");
}

// The small ball touching the big one: its sphere could uncover particles its own hid, so
// both paths draw every particle of the others unculled while it is replaced. One GPU
// renderer follows a camera that comes near (nothing replaced: culled), backs away (the small
// ball replaced: the marks redone without culling) and comes near again, each frame as the
// CPU's.
TEST_F(RendererTest, TheGpuPathTurnsTheCullingOffWhereTheCpuPathDoes) {
    TestScene t = ballsAndPair({1.45f, -0.3f, 0.4f}, false);
    Renderer gpu(device, perSetSettings(PerSetDevice::Gpu, 20.0));
    Renderer cpu(device, perSetSettings(PerSetDevice::Cpu, 20.0));
    double culled = 0.0;
    for (const double distance : {2.5, 5.0, 2.5}) {
        t.scene.camera.position = {0.0, 0.0, distance};
        const core::RenderInput in{t.scene, t.particles, t.materials};
        const core::Frame g = gpu.render(in);
        const core::Frame c = cpu.render(in);
        const std::string what = fmt::format("camera at {}", distance);
        expectTheSameFrame(g, c, what.c_str());
        if (distance == 2.5) {
            EXPECT_EQ(c.counters.at("body_spheres"), 0.0);
            culled = c.counters.at("particles_drawn");
        } else {
            EXPECT_EQ(c.counters.at("body_spheres"), 1.0);
            // The ball unculled: more than its share of the surface.
            EXPECT_GT(c.counters.at("particles_drawn"), 2.0 * culled);
        }
    }
}

// The self-check (doctor, --self-check) renders through both paths with the scene's settings,
// the body spheres too: it passes where both replace the same bodies.
TEST_F(RendererTest, TheSelfCheckPassesWithBodySpheresOnBothPaths) {
    TestScene t = ballsAndPair({-1.9f, 0.5f, 0.0f}, true);
    const SelfCheck check = selfCheck(device, perSetSettings(PerSetDevice::Gpu, 20.0),
                                      {t.scene, t.particles, t.materials});
    EXPECT_TRUE(check.passed()) << check.table();
}

// A frame whose threshold replaces no body runs the programs a frame without the key runs:
// the same image bit for bit, the same counts.
TEST_F(RendererTest, AGpuFrameThatReplacesNoBodyIsUnchangedBitForBit) {
    TestScene t = ballsAndPair({-1.9f, 0.5f, 0.0f}, true);
    const core::Frame off = render(t, perSetSettings(PerSetDevice::Gpu, 0.0));
    const core::Frame on = render(t, perSetSettings(PerSetDevice::Gpu, 1e-3));
    EXPECT_EQ(on.counters.at("body_spheres"), 0.0);
    for (const char* counter : {"particles_drawn", "droplets"})
        EXPECT_EQ(on.counters.at(counter), off.counters.at(counter)) << counter;
    ASSERT_EQ(on.image.pixels().size(), off.image.pixels().size());
    EXPECT_EQ(std::memcmp(on.image.pixels().data(), off.image.pixels().data(),
                          on.image.pixels().size() * sizeof(float)),
              0);
}

}  // namespace
}  // namespace twinrender::realtime
