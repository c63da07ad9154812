// Renderer tests on llvmpipe: small images (160 x 90) and few particles. Scenes are built in
// code so that uv, normals and bodies are exactly what each test needs.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <limits>

#include "core/camera.h"
#include "core/shading.h"
#include "core/stage_table.h"
#include "realtime/gl/context.h"
#include "realtime/renderer.h"
#include "realtime/testing/gl_test_scene.h"

namespace twinrender::realtime {
namespace {

using testing::Channels;
using testing::constantTexture;
using testing::cube;
using testing::HEIGHT;
using testing::quiet;
using testing::RendererTest;
using testing::TestScene;
using testing::WIDTH;

// One particle: the disc it covers, its linear eye depth in Z, its id; the background keeps
// the AOV background values. In every depth mode.
TEST_F(RendererTest, OneSphereHasExactDepthAndCoverageInEveryMode) {
    for (DepthMode mode : {DepthMode::Standard, DepthMode::Log, DepthMode::Reversed}) {
        TestScene t;
        const float h = 1.0f;
        t.add(0, {0.0f, 0.0f, 0.0f}, h);
        Settings s = quiet();
        s.depth = mode;
        s.ssss.enabled = true;  // ssss and shade draw covered pixels only, by depth test
        const core::Frame r = render(t, s);
        const Channels c{r.image};
        const core::Camera camera(t.scene.camera);
        const double radius = s.particles.radiusScale * h;
        int covered = 0, expected = 0;
        for (int y = 0; y < HEIGHT; ++y)
            for (int x = 0; x < WIDTH; ++x) {
                const core::Ray ray = camera.ray(x + 0.5, y + 0.5);
                // Ray-sphere in double precision.
                const double b = glm::dot(ray.origin, ray.direction);
                const double disc = b * b - (glm::dot(ray.origin, ray.origin) - radius * radius);
                const bool hit = disc > 0.0;
                // Pixels within 1e-3 of the silhouette may go either way.
                if (std::abs(disc) < 1e-3) continue;
                expected += hit;
                covered += c(x, y, "A") > 0.5f;
                if (hit) {
                    const double t0 = -b - std::sqrt(disc);
                    const double z = camera.eyeDepth(ray.origin + t0 * ray.direction);
                    ASSERT_NEAR(c(x, y, "Z"), z, 2e-5 * z)
                        << toString(mode) << " " << x << "," << y;
                    ASSERT_EQ(c(x, y, "id"), 0.0f);
                    ASSERT_EQ(c(x, y, "A"), 1.0f);
                    ASSERT_GT(c(x, y, "R"), 0.0f);  // lit from behind the camera
                    ASSERT_EQ(c(x, y, "shadow"), 1.0f);
                } else {
                    ASSERT_EQ(c(x, y, "A"), 0.0f) << x << "," << y;
                    ASSERT_EQ(c(x, y, "id"), -1.0f);
                    ASSERT_TRUE(std::isinf(c(x, y, "Z")));
                    ASSERT_EQ(c(x, y, "R"), 0.0f);
                }
            }
        EXPECT_EQ(covered, expected) << toString(mode);
        EXPECT_GT(expected, 100);
        EXPECT_EQ(r.renderer, "realtime");
        EXPECT_EQ(r.device, context.renderer());
    }
}

// far / near = 1e10 (a telescope): two bodies 0.1 % apart in depth, far away. The log and
// reversed buffers keep the nearer body in front; the 24-bit standard buffer cannot tell them
// apart and shows the one drawn first (here the farther one).
TEST_F(RendererTest, LogDepthKeepsFarBodiesInOrderWhereStandardDoesNot) {
    std::map<DepthMode, int> wrong;
    for (DepthMode mode : {DepthMode::Standard, DepthMode::Log, DepthMode::Reversed}) {
        TestScene t;
        t.scene.camera.position = {0.0, 0.0, 0.0};
        t.scene.camera.target = {0.0, 0.0, -1.0};
        t.scene.camera.near = 1e-3;
        t.scene.camera.far = 1e7;
        t.scene.camera.fovYDeg = 0.5;
        Settings s = quiet();
        s.depth = mode;
        s.particles.cullHidden = false;
        const double radius = 300.0;  // scene units
        const auto h = static_cast<float>(radius / s.particles.radiusScale);
        t.add(1, {150.0f, 0.0f, -100200.0f}, h);  // farther, drawn first
        t.add(0, {-150.0f, 0.0f, -100000.0f}, h);
        const core::Frame r = render(t, s);
        const Channels c{r.image};
        const core::Camera camera(t.scene.camera);
        for (int y = 0; y < HEIGHT; ++y)
            for (int x = 0; x < WIDTH; ++x) {
                // The nearest sphere along the pixel's ray, in double precision.
                const core::Ray ray = camera.ray(x + 0.5, y + 0.5);
                double best = std::numeric_limits<double>::infinity();
                double hits[2] = {best, best};
                float id = -1.0f;
                bool silhouette = false;
                for (std::size_t i = 0; i < 2; ++i) {
                    const glm::dvec3 oc = -glm::dvec3(t.particles.particles.position[i]);
                    const double b = glm::dot(oc, ray.direction);
                    const double disc = b * b - (glm::dot(oc, oc) - radius * radius);
                    // Pixels within a thousandth of a radius of an outline may go either way.
                    silhouette |= std::abs(disc) < 1e-3 * radius * radius;
                    if (disc < 0.0) continue;
                    const double d = -b - std::sqrt(disc);
                    hits[i] = d;
                    if (d < best) {
                        best = d;
                        id = static_cast<float>(t.particles.particles.body[i]);
                    }
                }
                // Where the spheres cut each other both are at the same depth: not an order.
                const bool tie = std::abs(hits[0] - hits[1]) < 1e-5 * best;
                if (!silhouette && !tie && id >= 0.0f && c(x, y, "id") != id) ++wrong[mode];
            }
    }
    EXPECT_EQ(wrong[DepthMode::Log], 0);
    EXPECT_EQ(wrong[DepthMode::Reversed], 0);
    EXPECT_GT(wrong[DepthMode::Standard], 100);
}

// The shade pass is core::shade, and post (without bloom) is core::tonemap.
TEST_F(RendererTest, ShadingMatchesTheCoreModel) {
    TestScene t;
    core::Image diffuse(8, 4, {"R", "G", "B"}), city(2, 2, {"R", "G", "B"});
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
            for (int k = 0; k < 3; ++k)
                diffuse.at(x, y, k) = 0.1f + 0.8f * ((x * 3 + y * 5 + k) % 7) / 6.0f;
    city.at(1, 0, 0) = 2.0f;
    city.at(0, 1, 1) = 1.0f;
    core::Material& m = t.materials[0];
    m.diffuse = core::Texture(diffuse);
    m.specular = constantTexture({0.3f, 0.3f, 0.2f});
    m.emission = constantTexture({0.02f, 0.01f, 0.0f});
    m.cityLights = core::Texture(city);
    m.shininess = 20.0f;
    t.scene.light.direction = glm::normalize(glm::dvec3(-1.0, 0.3, -0.5));
    t.scene.light.color = {1.0, 0.9, 0.8};
    t.scene.camera.exposure = 1.3;
    // Particles with varied normals and uv gradients, a ball of 7 x 7 x 7.
    for (int z = -3; z <= 3; ++z)
        for (int y = -3; y <= 3; ++y)
            for (int x = -3; x <= 3; ++x) {
                const glm::vec3 p(x * 0.3f, y * 0.3f, z * 0.3f);
                const std::size_t i = t.add(0, p, 0.39f, {0.5f + 0.07f * x, 0.5f + 0.1f * y},
                                            glm::normalize(p + glm::vec3(0.01f, 0.02f, 0.03f)));
                t.particles.particles.dudx[i] = {0.2f, 0.05f, 0.0f};
                t.particles.particles.dvdx[i] = {0.0f, 0.3f, 0.1f};
                t.particles.particles.glow[i] = {0.1f * (x + 3), 0.0f, 0.0f};
            }
    const core::Frame r = render(t, quiet());
    const Channels c{r.image};
    const core::Camera camera(t.scene.camera);
    int checked = 0;
    for (int y = 0; y < HEIGHT; ++y)
        for (int x = 0; x < WIDTH; ++x) {
            const glm::vec3 beauty(c(x, y, "R"), c(x, y, "G"), c(x, y, "B"));
            const glm::vec3 display(r.display.at(x, y, 0), r.display.at(x, y, 1),
                                    r.display.at(x, y, 2));
            const glm::vec3 mapped = core::tonemap(beauty, 1.3f);
            for (int k = 0; k < 3; ++k) ASSERT_NEAR(display[k], mapped[k], 2e-5) << x << "," << y;
            if (c(x, y, "A") == 0.0f) continue;
            core::SurfacePoint p;
            p.normal = glm::vec3(c(x, y, "N.X"), c(x, y, "N.Y"), c(x, y, "N.Z"));
            p.toEye = -glm::vec3(camera.ray(x + 0.5, y + 0.5).direction);
            p.uv = {c(x, y, "uv.U"), c(x, y, "uv.V")};
            p.material = 0;
            p.emission =
                glm::vec3(c(x, y, "emission.R"), c(x, y, "emission.G"), c(x, y, "emission.B"));
            p.visibility = c(x, y, "shadow");
            const glm::vec3 expected = core::shade(t.materials, t.scene.light, p);
            for (int k = 0; k < 3; ++k)
                ASSERT_NEAR(beauty[k], expected[k], 1e-4f + 1e-4f * expected[k]) << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, 500);
}

// Two touching slabs with different uv ranges and normals: the blur never mixes them.
TEST_F(RendererTest, SmoothingNeverMixesTwoBodies) {
    for (bool separable : {true, false}) {
        TestScene t;
        const float s = 0.12f;
        t.slab(0, {-2.4f, -1.2f, 0.0f}, 20, 20, s,
               [](int x, int y) { return glm::vec2(0.1f + 0.005f * x, 0.2f + 0.005f * y); });
        t.slab(
            1, {0.0f, -1.2f, 0.0f}, 20, 20, s,
            [](int x, int y) { return glm::vec2(0.6f + 0.005f * x, 0.7f + 0.005f * y); },
            glm::normalize(glm::vec3(0.6f, 0.0f, 0.8f)));
        // Red glow on body 0, blue on body 1: the emission is smoothed too.
        for (std::size_t i = 0; i < t.particles.particles.size(); ++i)
            t.particles.particles.glow[i] =
                t.particles.particles.body[i] == 0 ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
        Settings settings = quiet();
        settings.ssss.enabled = true;
        settings.ssss.separable = separable;
        settings.ssss.radiusScale = 4.0;
        settings.ssss.iterations = 3;
        // One normal per body, to recognise it (the field model turns at the slabs' edges).
        settings.particles.normal = NormalModel::Blend;
        settings.particles.sphereNormalWeight = 0.0;
        const core::Frame r = render(t, settings);
        const Channels c{r.image};
        int pixels[2] = {0, 0};
        for (int y = 0; y < HEIGHT; ++y)
            for (int x = 0; x < WIDTH; ++x) {
                const float id = c(x, y, "id");
                if (id < 0.0f) continue;
                const int b = static_cast<int>(id);
                ++pixels[b];
                const float u = c(x, y, "uv.U"), v = c(x, y, "uv.V"), nx = c(x, y, "N.X");
                if (b == 0) {
                    ASSERT_TRUE(u >= 0.1f - 1e-6f && u <= 0.2f + 1e-6f) << u;
                    ASSERT_TRUE(v >= 0.2f - 1e-6f && v <= 0.3f + 1e-6f) << v;
                    ASSERT_NEAR(nx, 0.0f, 1e-6f);
                    ASSERT_EQ(c(x, y, "emission.B"), 0.0f);
                    ASSERT_NEAR(c(x, y, "emission.R"), 1.0f, 1e-6f);
                } else {
                    ASSERT_TRUE(u >= 0.6f - 1e-6f && u <= 0.7f + 1e-6f) << u;
                    ASSERT_NEAR(nx, 0.6f, 1e-5f);
                    ASSERT_EQ(c(x, y, "emission.R"), 0.0f);
                }
            }
        EXPECT_GT(pixels[0], 1000);
        EXPECT_GT(pixels[1], 1000);
    }
}

// Symmetric exclusion: at a pixel whose right neighbour belongs to another body, the pair
// (left, right) is excluded at every offset, so a body whose u varies only across columns keeps
// its unsmoothed u at its right edge. A one-sided kernel would pull it towards the left.
TEST_F(RendererTest, ExclusionIsSymmetric) {
    for (bool separable : {true, false}) {
        auto make = [&](bool smooth) {
            TestScene t;
            const float s = 0.12f;
            t.slab(0, {-2.4f, -1.2f, 0.0f}, 20, 20, s,
                   [](int x, int) { return glm::vec2(0.1f + 0.02f * x, 0.5f); });
            t.slab(1, {0.0f, -1.2f, 0.0f}, 20, 20, s,
                   [](int, int) { return glm::vec2(0.9f, 0.5f); });
            Settings settings = quiet();
            settings.ssss.enabled = smooth;
            settings.ssss.separable = separable;
            settings.ssss.radiusScale = 3.0;
            return render(t, settings);
        };
        const core::Frame off = make(false), on = make(true);
        const Channels a{off.image}, b{on.image};
        int edges = 0, smoothedInside = 0;
        for (int y = 0; y < HEIGHT; ++y)
            for (int x = 0; x + 1 < WIDTH; ++x) {
                if (a(x, y, "id") != 0.0f) continue;
                if (a(x + 1, y, "id") == 1.0f) {
                    // The edge column: its horizontal kernel is empty.
                    ASSERT_NEAR(b(x, y, "uv.U"), a(x, y, "uv.U"), 1e-6f) << x << "," << y;
                    ++edges;
                } else if (b(x, y, "uv.U") != a(x, y, "uv.U")) {
                    ++smoothedInside;
                }
            }
        EXPECT_GT(edges, 20);
        EXPECT_GT(smoothedInside, 500);  // the blur does act away from the edge
    }
}

// u wraps at the seam: averaging across u = 0.99 | 0.01 gives values near the seam, never 0.5.
TEST_F(RendererTest, SmoothingWrapsUAtTheSeam) {
    for (bool separable : {true, false}) {
        TestScene t;
        t.slab(0, {-1.2f, -1.2f, 0.0f}, 20, 20, 0.12f,
               [](int x, int) { return glm::vec2(std::fmod(0.95f + 0.01f * x, 1.0f), 0.5f); });
        Settings settings = quiet();
        settings.ssss.enabled = true;
        settings.ssss.separable = separable;
        settings.ssss.radiusScale = 4.0;
        settings.ssss.iterations = 2;
        const core::Frame r = render(t, settings);
        const Channels c{r.image};
        int nearSeam = 0;
        for (int y = 0; y < HEIGHT; ++y)
            for (int x = 0; x < WIDTH; ++x) {
                if (c(x, y, "id") < 0.0f) continue;
                const float u = c(x, y, "uv.U");
                ASSERT_TRUE(u >= 0.0f && u < 1.0f) << u;
                ASSERT_TRUE(u <= 0.16f || u >= 0.94f) << "u = " << u << " at " << x << "," << y;
                nearSeam += u > 0.98f || u < 0.02f;
            }
        EXPECT_GT(nearSeam, 50);
    }
}

// Occlusion culling changes the cost, never the image.
TEST_F(RendererTest, CullingHiddenParticlesLeavesTheImageUnchanged) {
    auto make = [&](bool cull) {
        TestScene t = cube(4);
        Settings s = quiet();
        s.shadows = ShadowMode::Map;
        s.ssss.enabled = true;
        s.particles.cullHidden = cull;
        return render(t, s);
    };
    const core::Frame culled = make(true), all = make(false);
    EXPECT_LT(culled.counters.at("particles_drawn"), 0.6 * all.counters.at("particles_drawn"));
    EXPECT_TRUE(culled.image == all.image);
}

// A recycled result's memory holds an older frame: the next frame overwrites all of it, and
// the cached culling answer is recomputed for a changed particle set.
TEST_F(RendererTest, RecycledFramesEqualFreshOnes) {
    Settings s = quiet();
    s.shadows = ShadowMode::Map;
    s.ssss.enabled = true;
    TestScene a = cube(3, 0.0f), b = cube(3, 2.0f);
    a.finish();
    b.finish();
    Renderer renderer(device, s);
    renderer.recycle(renderer.render({a.scene, a.particles, a.materials}));
    const core::Frame second = renderer.render({b.scene, b.particles, b.materials});
    Device freshDevice(context);
    const core::Frame expected =
        Renderer(freshDevice, s).render({b.scene, b.particles, b.materials});
    EXPECT_TRUE(second.image == expected.image);
    EXPECT_TRUE(second.display == expected.display);
}

// Renderers on one device share its programs and its answers per particle set; a renderer
// with other settings (another impostor radius: another culling answer and other field normals)
// renders what it renders on a device of its own.
TEST_F(RendererTest, RenderersSharingADeviceEqualFreshOnes) {
    TestScene t = cube(3);
    Settings small = quiet(), large = quiet();
    large.particles.radiusScale = 1.3;
    large.ssss.enabled = true;
    large.shadows = ShadowMode::Pcf;
    render(t, small);
    const core::Frame shared = render(t, large);
    Device freshDevice(context);
    const core::Frame fresh =
        Renderer(freshDevice, large).render({t.scene, t.particles, t.materials});
    EXPECT_TRUE(shared.image == fresh.image);
    EXPECT_TRUE(shared.display == fresh.display);
    EXPECT_EQ(shared.counters.at("particles_drawn"), fresh.counters.at("particles_drawn"));
}

// A small ball between the light and a slab, the light at 45 degrees (the shadow shifts to +x).
TestScene ballOverSlab() {
    TestScene t;
    t.scene.light.direction = glm::normalize(glm::dvec3(1.0, 0.0, -1.0));
    t.slab(0, {-3.0f, -1.6f, 0.0f}, 50, 27, 0.12f, [](int, int) { return glm::vec2(0.5f); });
    // A ball of radius 0.2 centred at (-1, 0, 1.5): 257 particles, over 5 % of the scene, so
    // the sphere baseline gives it an occluding sphere too.
    for (int z = -4; z <= 4; ++z)
        for (int y = -4; y <= 4; ++y)
            for (int x = -4; x <= 4; ++x)
                if (x * x + y * y + z * z <= 16)
                    t.add(1, glm::vec3(x * 0.05f - 1.0f, y * 0.05f, z * 0.05f + 1.5f), 0.065f,
                          {0.5f, 0.5f},
                          glm::normalize(glm::vec3(x, y, z) + glm::vec3(0.0f, 0.0f, 0.01f)));
    return t;
}

// The ball's shadow falls where the light's rays put it.
// The filtered maps ("esm" in both forms, "vsm", "evsm") too: fully lit where nothing is
// between, all but black (the exponential falls to e^-20 and below, the Chebyshev bound to
// 1e-4, under the bleed reduction) in the ball's umbra.
TEST_F(RendererTest, ShadowFallsWhereTheLightPutsIt) {
    for (const auto& [mode, form] :
         std::vector<std::pair<ShadowMode, EsmForm>>{{ShadowMode::Map, EsmForm::Warp},
                                                     {ShadowMode::Pcf, EsmForm::Warp},
                                                     {ShadowMode::Spheres, EsmForm::Warp},
                                                     {ShadowMode::None, EsmForm::Warp},
                                                     {ShadowMode::Esm, EsmForm::Warp},
                                                     {ShadowMode::Esm, EsmForm::Seed},
                                                     {ShadowMode::Vsm, EsmForm::Warp},
                                                     {ShadowMode::Evsm, EsmForm::Warp}}) {
        TestScene t = ballOverSlab();
        Settings s = quiet();
        s.shadows = mode;
        s.shadowMap.esmForm = form;
        const core::Frame r = render(t, s);
        const Channels c{r.image};
        const core::Camera camera(t.scene.camera);
        // The slab's surface (z ~ 0.15) below the ball's centre along the light.
        const glm::dvec2 shadowed = camera.project({-1.0 + 1.35, 0.0, 0.15});
        const glm::dvec2 lit = camera.project({2.0, 1.0, 0.1});
        const int sx = int(shadowed.x), sy = int(shadowed.y), lx = int(lit.x), ly = int(lit.y);
        ASSERT_EQ(c(sx, sy, "id"), 0.0f);
        EXPECT_EQ(c(lx, ly, "shadow"), 1.0f) << toString(mode);
        if (usesFilteredShadowMap(mode))
            EXPECT_LT(c(sx, sy, "shadow"), 1e-3f) << toString(mode) << " " << toString(form);
        else
            EXPECT_EQ(c(sx, sy, "shadow"), mode == ShadowMode::None ? 1.0f : 0.0f)
                << toString(mode);
        EXPECT_EQ(r.timingsMs.at("shadow") > 0.0, usesShadowMap(mode)) << toString(mode);
    }
}

// Under a sun of 5 degrees, pcf widens its filter to the penumbra: the ball's shadow, 1.5 units
// above the slab, gets an edge about 0.26 units wide in which the visibility is fractional,
// where the point sun's filter of 1.5 texels leaves a few pixels (measured: 53 pixels against
// 7). The umbra stays black.
TEST_F(RendererTest, PcfWidensItsFilterToTheSunsPenumbra) {
    auto fractional = [](const core::Frame& r) {
        const Channels c{r.image};
        int n = 0;
        for (int y = 0; y < r.image.height(); ++y)
            for (int x = 0; x < r.image.width(); ++x) {
                const float v = c(x, y, "shadow");
                n += c(x, y, "id") == 0.0f && v > 0.0f && v < 1.0f;
            }
        return n;
    };
    TestScene t = ballOverSlab();
    Settings s = quiet();
    s.shadows = ShadowMode::Pcf;
    const int point = fractional(render(t, s));
    t.scene.light.angularRadiusDeg = 5.0;
    const core::Frame soft = render(t, s);
    EXPECT_GT(fractional(soft), 2 * point + 20) << point;
    const glm::dvec2 umbra = core::Camera(t.scene.camera).project({-1.0 + 1.35, 0.0, 0.15});
    EXPECT_EQ(Channels{soft.image}(int(umbra.x), int(umbra.y), "shadow"), 0.0f);
}

// gbuffer.format = "compact": normal + uv and emission in half floats, 32 bytes a pixel for 48.
// The same coverage; the octahedral normal rounds by up to half an ulp of a half float near 1
// (4.9e-4), under 0.1 degrees; u and v (up to 1.05 at the slab's edge) by up to half an ulp
// below 2, 4.9e-4 (measured 3.3e-4); the gradient pass's own
// targets, the smoothing's and the shading are 32-bit either way.
TEST_F(RendererTest, CompactGBufferKeepsNormalsAndUvWithinHalfPrecision) {
    TestScene t;
    t.slab(0, {-1.0f, -1.0f, 0.0f}, 12, 12, 0.2f,
           [](int x, int y) { return glm::vec2(x / 12.0f, y / 12.0f); });
    t.finish();
    Settings full = quiet();
    full.surface.method = SurfaceMethod::None;
    Settings compact = full;
    compact.gbufferFormat = GBufferFormat::Compact;
    const core::Frame a = render(t, full), b = render(t, compact);
    EXPECT_EQ(a.counters.at("gbuffer_bytes"), 52.0 * WIDTH * HEIGHT);
    EXPECT_EQ(b.counters.at("gbuffer_bytes"), 36.0 * WIDTH * HEIGHT);
    const Channels ca{a.image}, cb{b.image};
    int covered = 0;
    double worstDegrees = 0.0, worstUv = 0.0;
    for (int y = 0; y < HEIGHT; ++y)
        for (int x = 0; x < WIDTH; ++x) {
            ASSERT_EQ(ca(x, y, "A"), cb(x, y, "A")) << x << "," << y;
            if (ca(x, y, "A") == 0.0f) continue;
            ++covered;
            const glm::dvec3 na(ca(x, y, "N.X"), ca(x, y, "N.Y"), ca(x, y, "N.Z")),
                nb(cb(x, y, "N.X"), cb(x, y, "N.Y"), cb(x, y, "N.Z"));
            const double cosine = glm::dot(na, nb) / (glm::length(na) * glm::length(nb));
            worstDegrees = std::max(worstDegrees, std::acos(std::min(cosine, 1.0)) * 180.0 / M_PI);
            worstUv = std::max({worstUv, double(std::abs(ca(x, y, "uv.U") - cb(x, y, "uv.U"))),
                                double(std::abs(ca(x, y, "uv.V") - cb(x, y, "uv.V")))});
        }
    ASSERT_GT(covered, 100);
    EXPECT_LT(worstDegrees, 0.1);
    EXPECT_LE(worstUv, 4.9e-4);
    EXPECT_GT(worstUv, 0.0) << "the compact targets must round: half floats hold no more";
}

// Every stage a frame times is a row of core/stage_table.h (the reports, sweeps and studies
// order and describe stages from it), on both per-set paths and with the optional passes on.
TEST_F(RendererTest, EveryTimedStageIsInTheStageTable) {
    TestScene t;
    t.slab(0, {-1.0f, -1.0f, 0.0f}, 8, 8, 0.25f,
           [](int x, int y) { return glm::vec2(x / 8.0f, y / 8.0f); });
    t.finish();
    for (const PerSetDevice where : {PerSetDevice::Cpu, PerSetDevice::Gpu}) {
        Settings s;
        s.perSet = where;
        s.shadows = ShadowMode::Pcf;
        s.particles.normal = NormalModel::Gradient;
        s.particles.shape = ParticleShape::Ellipsoid;
        const core::Frame f = render(t, s);
        ASSERT_FALSE(f.timingsMs.empty());
        for (const auto& [stage, ms] : f.timingsMs)
            EXPECT_NE(core::findStage(stage), nullptr) << stage << " (" << toString(where) << ")";
    }
}

TEST_F(RendererTest, PassesTheSettingsDoNotNeedDoNotRun) {
    TestScene t;
    t.add(0, {0.0f, 0.0f, 0.0f}, 1.0f);
    const core::Frame r = render(t, quiet());
    EXPECT_EQ(r.timingsMs.at("shadow"), 0.0);
    EXPECT_EQ(r.timingsMs.at("ssss"), 0.0);
    EXPECT_GT(r.timingsMs.at("gbuffer"), 0.0);
    for (const char* key :
         {"total", "upload", "shadow", "gbuffer", "ssss", "shade", "post", "readback"})
        EXPECT_TRUE(r.timingsMs.count(key)) << key;
    EXPECT_EQ(r.settings.at("realtime.shadows"), "none");
    // The default occlusion method without a reach (the scene's light.ao_radius is 0): no pass.
    EXPECT_EQ(r.settings.at("realtime.ao.method"), "traced");
    EXPECT_EQ(r.timingsMs.at("ao"), 0.0);
    // The background carries core::aov::makeImage's values in every channel.
    const core::Image background = core::aov::makeImage(1, 1);
    ASSERT_EQ(r.image.channelNames(), background.channelNames());
    for (int c = 0; c < background.channelCount(); ++c)
        EXPECT_EQ(r.image.at(0, 0, c), background.at(0, 0, c)) << background.channelNames()[c];
}

}  // namespace
}  // namespace twinrender::realtime
