// The surface filters (realtime.surface.method): each keeps a flat slab flat, brings the
// normals of a ball of sphere impostors closer to the analytic sphere's, keeps every body's
// depth and normals to itself; the user's shader interface copies what it leaves alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/error.h"
#include "realtime/testing/gl_test_scene.h"

namespace twinrender::realtime {
namespace {

using testing::Channels;
using testing::HEIGHT;
using testing::quiet;
using testing::RendererTest;
using testing::TestScene;
using testing::WIDTH;

constexpr SurfaceMethod DEPTH_FILTERS[] = {SurfaceMethod::Bilateral, SurfaceMethod::NarrowRange,
                                           SurfaceMethod::CurvatureFlow};

// Spheres of radius 0.9 h with their own normals (no colour-field model): what the depth
// filters were made for.
Settings spheres(SurfaceMethod method) {
    Settings s = quiet();
    s.particles.normal = NormalModel::Blend;
    s.particles.sphereNormalWeight = 1.0;
    s.surface.method = method;
    return s;
}

// The variants of each filter the tests run: its defaults, and its other kernel shape.
std::vector<Settings> variants(SurfaceMethod method) {
    std::vector<Settings> out{spheres(method)};
    if (method == SurfaceMethod::Bilateral) {
        out.push_back(out[0]);
        out.back().surface.bilateral.separable = true;
    } else if (method == SurfaceMethod::NarrowRange) {
        out.push_back(out[0]);
        out.back().surface.narrowRange.separable = false;
    }
    return out;
}

std::string describe(const Settings& s) {
    return toJson(s).dump();
}

double angleDeg(glm::dvec3 a, glm::dvec3 b) {
    return glm::degrees(
        std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)));
}

glm::dvec3 normalAt(const Channels& c, int x, int y) {
    return {c(x, y, "N.X"), c(x, y, "N.Y"), c(x, y, "N.Z")};
}

// A slab of 2 x 40 x 26 particles facing the camera: the filtered normals stay within 12
// degrees of the plane's on average, and within 25 degrees at the 95th percentile, away from
// its edges (4 pixels), where the spheres' own normals are 27 degrees off on average. The
// bounds: the spheres' caps bulge 0.1 s between particles 2.6 pixels apart.
TEST_F(RendererTest, DepthFiltersKeepAFlatSlabFlat) {
    TestScene base;
    base.slab(0, {-2.4f, -1.5f, 0.0f}, 40, 26, 0.12f, [](int, int) { return glm::vec2(0.5f); });
    for (SurfaceMethod method : DEPTH_FILTERS)
        for (const Settings& settings : variants(method)) {
            TestScene t = base;
            const core::Frame f = render(t, settings);
            const Channels c{f.image};
            std::vector<double> angles;
            for (int y = 4; y < HEIGHT - 4; ++y)
                for (int x = 4; x < WIDTH - 4; ++x) {
                    bool inside = true;
                    for (int dy = -4; dy <= 4 && inside; dy += 4)
                        for (int dx = -4; dx <= 4 && inside; dx += 4)
                            inside = c(x + dx, y + dy, "id") == 0.0f;
                    if (inside) angles.push_back(angleDeg(normalAt(c, x, y), {0, 0, 1}));
                }
            ASSERT_GT(angles.size(), 3000u);
            std::sort(angles.begin(), angles.end());
            double mean = 0.0;
            for (double a : angles) mean += a / double(angles.size());
            EXPECT_LT(mean, 12.0) << describe(settings);
            EXPECT_LT(angles[angles.size() * 95 / 100], 25.0) << describe(settings);
        }
}

// The mean angle between the frame's normals and those of the sphere of centre `centre`
// through each covered pixel's surface point (from its eye depth).
double ballNormalErrorDeg(const core::Frame& f, const core::Camera& camera, glm::dvec3 centre) {
    const Channels c{f.image};
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < HEIGHT; ++y)
        for (int x = 0; x < WIDTH; ++x) {
            if (c(x, y, "id") < 0.0f) continue;
            const core::Ray ray = camera.ray(x + 0.5, y + 0.5);
            const double t = c(x, y, "Z") / glm::dot(ray.direction, camera.forward());
            const glm::dvec3 p = ray.origin + t * ray.direction;
            sum += angleDeg(normalAt(c, x, y), p - centre);
            ++n;
        }
    return n > 0 ? sum / n : NAN;
}

// A ball of particles on a cubic lattice: every filter brings the normals closer to the
// analytic sphere's than the spheres' own normals are (27 degrees off on average).
TEST_F(RendererTest, DepthFiltersLowerTheNormalErrorOfABall) {
    TestScene base;
    const float s = 0.1f;
    for (int z = -12; z <= 12; ++z)
        for (int y = -12; y <= 12; ++y)
            for (int x = -12; x <= 12; ++x)
                if (x * x + y * y + z * z <= 144)
                    base.add(0, glm::vec3(x, y, z) * s, 1.3f * s, {0.5f, 0.5f},
                             glm::normalize(glm::vec3(x, y, z) + glm::vec3(1e-3f)));
    const core::Camera camera(base.scene.camera);
    TestScene plain = base;
    const double none = ballNormalErrorDeg(render(plain, spheres(SurfaceMethod::None)), camera, {});
    EXPECT_GT(none, 15.0);
    for (SurfaceMethod method : DEPTH_FILTERS)
        for (const Settings& settings : variants(method)) {
            TestScene t = base;
            const double error = ballNormalErrorDeg(render(t, settings), camera, {});
            EXPECT_LT(error, 0.7 * none) << describe(settings);
        }
}

// Two slabs 3 units apart, the near one (body 0) covering the left of the far one (body 1):
// a near-body pixel's depth and normal are exactly those of the near slab rendered alone; no
// pixel gets a depth between the slabs; the far slab's normals next to the near one do not
// turn towards it (within 30 degrees of the view, where the spheres' own are up to 90 off),
// away from the far slab's own outline.
TEST_F(RendererTest, DepthFiltersKeepEachBodyToItself) {
    auto scene = [](bool withFar) {
        TestScene t;
        t.slab(0, {-2.4f, -1.5f, 0.0f}, 22, 26, 0.12f, [](int, int) { return glm::vec2(0.5f); });
        if (withFar)
            t.slab(1, {-0.6f, -1.8f, -3.0f}, 30, 32, 0.12f,
                   [](int, int) { return glm::vec2(0.5f); });
        return t;
    };
    for (SurfaceMethod method : DEPTH_FILTERS)
        for (const Settings& settings : variants(method)) {
            TestScene both = scene(true), nearOnly = scene(false);
            const core::Frame f = render(both, settings), alone = render(nearOnly, settings);
            const Channels c{f.image}, a{alone.image};
            int nearPixels = 0, boundary = 0;
            for (int y = 1; y < HEIGHT - 1; ++y)
                for (int x = 1; x < WIDTH - 1; ++x) {
                    const float id = c(x, y, "id"), z = c(x, y, "Z");
                    if (id < 0.0f) continue;
                    ASSERT_TRUE(z < 10.5f || z > 12.5f) << describe(settings) << " " << z;
                    if (id == 0.0f) {
                        ++nearPixels;
                        ASSERT_EQ(z, a(x, y, "Z")) << describe(settings);
                        ASSERT_EQ(normalAt(c, x, y), normalAt(a, x, y)) << describe(settings);
                    } else if (c(x - 1, y, "id") == 0.0f && c(x + 1, y, "id") == 1.0f &&
                               c(x, y - 1, "id") == 1.0f && c(x, y + 1, "id") == 1.0f) {
                        ++boundary;
                        EXPECT_LT(angleDeg(normalAt(c, x, y), {0, 0, 1}), 30.0)
                            << describe(settings) << " at " << x << ", " << y;
                    }
                }
            EXPECT_GT(nearPixels, 1000);
            EXPECT_GT(boundary, 20);
        }
}

Settings userShader(const std::string& file) {
    Settings s = quiet();
    s.surface.method = SurfaceMethod::Shader;
    s.surface.shaderPath = file;
    s.surface.shaderSource = "void filterSurface(ivec2 pixel, inout SurfaceSample s) {}\n";
    return s;
}

// The pass-through shader gives the image of "none", bit for bit, with and without emission
// and shadows.
TEST_F(RendererTest, PassThroughShaderEqualsNone) {
    for (bool glow : {false, true}) {
        TestScene base = testing::cube(4);
        if (glow)
            for (auto& g : base.particles.particles.glow) g = glm::vec3(0.5f, 0.2f, 0.1f);
        Settings none = quiet(), pass = userShader("pass_through.glsl");
        none.surface.method = SurfaceMethod::None;
        none.shadows = pass.shadows = ShadowMode::Pcf;
        none.bloom.enabled = pass.bloom.enabled = true;
        TestScene a = base, b = base;
        const core::Frame expected = render(a, none), got = render(b, pass);
        EXPECT_TRUE(got.image == expected.image) << glow;
        EXPECT_TRUE(got.display == expected.display) << glow;
        EXPECT_GT(got.timingsMs.at("surface"), 0.0);
    }
}

// What a user's shader writes reaches the frame: depth pushed back by a constant, emission set
// (in a scene that emits: elsewhere the emission buffer is never read).
TEST_F(RendererTest, UserShaderWritesDepthAndEmission) {
    Settings s = userShader("push.glsl");
    s.surface.shaderSource =
        "void filterSurface(ivec2 pixel, inout SurfaceSample s) {\n"
        "    s.depth += 0.25;\n"
        "    s.emission = vec3(0.0, 1.0, 0.0);\n"
        "}\n";
    TestScene a = testing::cube(2), b = testing::cube(2);
    // The emission buffer is read only where something emits.
    for (TestScene* t : {&a, &b})
        for (auto& g : t->particles.particles.glow) g = glm::vec3(0.1f, 0.0f, 0.0f);
    const core::Frame base = render(a, quiet()), pushed = render(b, s);
    const Channels c{base.image}, p{pushed.image};
    int covered = 0;
    for (int y = 0; y < HEIGHT; ++y)
        for (int x = 0; x < WIDTH; ++x) {
            if (c(x, y, "id") < 0.0f) continue;
            ++covered;
            ASSERT_NEAR(p(x, y, "Z"), c(x, y, "Z") + 0.25f, 1e-5f);
            ASSERT_EQ(p(x, y, "emission.G"), 1.0f);
        }
    EXPECT_GT(covered, 400);
}

// A shader that does not compile is bad input, named with the compiler's line, before any
// frame is rendered.
TEST_F(RendererTest, BrokenUserShaderIsBadInputNamingTheLine) {
    Settings s = userShader("broken.glsl");
    s.surface.shaderSource =
        "void filterSurface(ivec2 pixel, inout SurfaceSample s) {\n"
        "    s.depth = undefinedThing;\n"
        "}\n";
    try {
        Renderer renderer(device, s);
        FAIL() << "no error";
    } catch (const core::InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("broken.glsl:2:"), std::string::npos) << what;
        EXPECT_NE(what.find("undefinedThing"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace twinrender::realtime
