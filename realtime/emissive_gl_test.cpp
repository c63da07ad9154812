// The emissive pass (realtime.emissive.*) on llvmpipe: a glowing ball of particles over a slab,
// seen from above. The point lights give the closed form of a glowing sphere; the screen-space
// rays light the slab next to the ball and nothing once the ball is off screen, unless marched
// in the wider emitter target ("ssem_target"); without
// light.emissive_light nothing changes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "core/camera.h"
#include "core/emitters.h"
#include "realtime/program_variants.h"
#include "realtime/testing/gl_test_scene.h"

namespace twinrender::realtime {
namespace {

using testing::Channels;
using testing::constantTexture;
using testing::quiet;
using testing::RendererTest;
using testing::TestScene;

const glm::vec3 RADIANCE(2.0f, 1.0f, 0.5f);

// A slab (body 0) in the plane z = 0 facing the camera at (0, 0, 10), and a ball of radius 0.2
// (body 1) of uniform emitted radiance RADIANCE centred at `centre`, 1.5 above it.
TestScene glowingBallOverSlab(glm::vec3 centre = {-1.0f, 0.0f, 1.5f}) {
    TestScene t;
    t.scene.light.emissiveLight = true;
    t.scene.light.intensity = 0.0;
    t.slab(0, {-3.0f, -1.6f, 0.0f}, 50, 27, 0.12f, [](int, int) { return glm::vec2(0.5f); });
    const std::size_t slab = t.particles.particles.size();
    core::Material glowing = t.materials[0];
    glowing.name = "glowing";
    glowing.diffuse = constantTexture(glm::vec3(0.0f));
    glowing.emission = constantTexture(RADIANCE);
    t.materials.push_back(glowing);
    for (int z = -4; z <= 4; ++z)
        for (int y = -4; y <= 4; ++y)
            for (int x = -4; x <= 4; ++x)
                if (x * x + y * y + z * z <= 16) {
                    const std::size_t i =
                        t.add(1, centre + glm::vec3(x, y, z) * 0.05f, 0.065f, {0.5f, 0.5f},
                              glm::normalize(glm::vec3(x, y, z) + glm::vec3(0.0f, 0.0f, 0.01f)));
                    t.particles.particles.material[i] = 1;
                }
    // The bodies' particle ranges and materials, as the scene loader sets them
    // (core::emittingBodies reads them).
    t.particles.bodies[0].end = slab;
    t.particles.bodies[1] = {
        .name = "", .material = 1, .begin = slab, .end = t.particles.particles.size()};
    return t;
}

// The world position of pixel (x, y)'s surface, from its eye depth Z.
glm::dvec3 surfacePoint(const core::Camera& camera, const Channels& c, int x, int y) {
    const core::Ray ray = camera.ray(x + 0.5, y + 0.5);
    return ray.origin +
           ray.direction * (double(c(x, y, "Z")) / glm::dot(ray.direction, camera.forward()));
}

glm::dvec3 irradianceAt(const Channels& c, int x, int y) {
    return {c(x, y, "irradiance.R"), c(x, y, "irradiance.G"), c(x, y, "irradiance.B")};
}

Settings withMethod(EmissiveMethod method) {
    Settings s = quiet();
    s.emissive.method = method;
    return s;
}

// The screen-space rays' settings for a 160 x 90 image where the ball is 8 pixels across:
// steps of under 2 pixels, so that a ray does not step over it, and a shell of 4 particle
// radii, half the ball's depth. Seen face-on from above, a thicker one stands a column under
// the ball that rays passing below it meet (the default 16: 3.7 times the closed form at 0.6).
Settings screenSpace() {
    Settings s = withMethod(EmissiveMethod::Ssem);
    s.emissive.steps = 32;
    s.emissive.maxPixels = 48.0;
    s.emissive.thickness = 4.0;
    return s;
}

// Each body a point source of intensity pi R^2 L: on the slab the irradiance of a glowing
// sphere of the body's surface radius R, E = pi L (R / d)^2 cos(theta), wherever the sphere
// lies wholly above the horizon; the ball is not lit by its own point.
TEST_F(RendererTest, PointLightsGiveTheClosedFormOfAGlowingSphere) {
    TestScene t = glowingBallOverSlab();
    t.finish();
    const std::vector<core::EmittingBody> bodies = core::emittingBodies(t.particles, t.materials);
    ASSERT_EQ(bodies.size(), 1u);
    const glm::dvec3 centre = bodies[0].centre;
    const double radius = bodies[0].surfaceRadius;
    const core::Frame f = render(t, withMethod(EmissiveMethod::PointLights));
    EXPECT_EQ(f.counters.at("point_lights"), 1.0);
    EXPECT_GT(f.timingsMs.at("emissive"), 0.0);
    const Channels c{f.image};
    const core::Camera camera(t.scene.camera);
    int floor = 0, ball = 0;
    for (int y = 0; y < f.image.height(); ++y)
        for (int x = 0; x < f.image.width(); ++x) {
            const glm::dvec3 e = irradianceAt(c, x, y);
            if (c(x, y, "id") == 1.0f) {
                EXPECT_EQ(e, glm::dvec3(0.0)) << x << " " << y;
                ++ball;
                continue;
            }
            if (c(x, y, "id") != 0.0f) continue;
            const glm::dvec3 p = surfacePoint(camera, c, x, y);
            const glm::dvec3 n =
                glm::normalize(glm::dvec3(c(x, y, "N.X"), c(x, y, "N.Y"), c(x, y, "N.Z")));
            const glm::dvec3 v = centre - p;
            const double d = glm::length(v), cosTheta = glm::dot(n, v) / d;
            if (std::acos(cosTheta) + std::asin(radius / d) > 0.5 * std::numbers::pi) continue;
            // The shader evaluates the same expression in 32-bit floats, from camera-relative
            // positions rebuilt from the same depth: a relative error of a few float ulps
            // (~1e-6) in each of d, cos(theta) and R, 1e-4 with room.
            for (int k = 0; k < 3; ++k) {
                const double expected =
                    std::numbers::pi * RADIANCE[k] * (radius / d) * (radius / d) * cosTheta;
                EXPECT_NEAR(e[k], expected, 1e-4 * expected) << x << " " << y << " " << k;
            }
            ++floor;
        }
    EXPECT_GT(floor, 5000);
    EXPECT_GT(ball, 20);
    // The shading adds albedo E / pi to what it gave without (the slab's albedo 0.5).
    const core::Frame dark = render(t, withMethod(EmissiveMethod::None));
    EXPECT_EQ(dark.timingsMs.at("emissive"), 0.0);
    const Channels u{dark.image};
    int lit = 0;
    for (int y = 0; y < f.image.height(); ++y)
        for (int x = 0; x < f.image.width(); ++x) {
            if (c(x, y, "id") != 0.0f || c(x, y, "irradiance.R") < 0.01f) continue;
            const double expected = 0.5 * c(x, y, "irradiance.R") / std::numbers::pi;
            EXPECT_NEAR(c(x, y, "R") - u(x, y, "R"), expected, 1e-4 * expected + 1e-6);
            ++lit;
        }
    EXPECT_GT(lit, 1000);
}

// The screen-space rays light the slab next to the ball, the more the nearer; with the ball
// off screen they light nothing, where the point lights (and the reference) still do: the
// failure the method is measured for.
TEST_F(RendererTest, ScreenSpaceEmissiveLightsOnlyWhatItSeesEmit) {
    TestScene near = glowingBallOverSlab();
    const core::Frame on = render(near, screenSpace());
    const Channels c{on.image};
    const core::Camera camera(near.scene.camera);
    auto meanAt = [&](const Channels& ch, double distance) {
        double sum = 0.0;
        int n = 0;
        for (int i = 0; i < 16; ++i) {
            const double a = 2.0 * std::numbers::pi * i / 16.0;
            const glm::dvec2 q =
                camera.project({-1.0 + distance * std::cos(a), distance * std::sin(a), 0.1});
            if (ch(int(q.x), int(q.y), "id") != 0.0f) continue;
            sum += ch(int(q.x), int(q.y), "irradiance.R");
            ++n;
        }
        return n > 0 ? sum / n : -1.0;
    };
    const double close = meanAt(c, 0.6), far = meanAt(c, 1.6);
    EXPECT_GT(close, 0.0);
    EXPECT_GT(close, far);
    // Near the point lights' closed form: the rays meet the impostors, which reach past the
    // surface radius the point stands in for (0.9 h past the outermost centres, against 0.5 h),
    // a solid angle (0.259 / 0.233)^2 = 1.24 times the sphere's (measured: 1.16 at 0.6, 1.19 at
    // 1.6); factors of 1.5 leave room for the rays' noise.
    const core::Frame points = render(near, withMethod(EmissiveMethod::PointLights));
    const double closeForm = meanAt(Channels{points.image}, 0.6),
                 farForm = meanAt(Channels{points.image}, 1.6);
    EXPECT_GT(close, closeForm / 1.5);
    EXPECT_LT(close, closeForm * 1.5);
    EXPECT_GT(far, farForm / 1.5);
    EXPECT_LT(far, farForm * 1.5);

    TestScene away = glowingBallOverSlab({6.0f, 0.0f, 1.5f});  // beyond the image's right edge
    const core::Frame off = render(away, screenSpace());
    const Channels o{off.image};
    double most = 0.0;
    int floor = 0;
    for (int y = 0; y < off.image.height(); ++y)
        for (int x = 0; x < off.image.width(); ++x) {
            ASSERT_NE(o(x, y, "id"), 1.0f) << "the ball is on screen";
            if (o(x, y, "id") != 0.0f) continue;
            most = std::max(most, double(o(x, y, "irradiance.R")));
            ++floor;
        }
    EXPECT_GT(floor, 5000);
    EXPECT_EQ(most, 0.0);
    const core::Frame offPoints = render(away, withMethod(EmissiveMethod::PointLights));
    const glm::dvec2 edge = camera.project({2.9, 0.0, 0.1});
    EXPECT_GT(Channels{offPoints.image}(int(edge.x), int(edge.y), "irradiance.R"), 0.0f);
}

// "ssem_target" marches the same rays in a target of the emitters alone with twice the view's
// tan(fov / 2): with the ball just beside the image (inside that wider view) "ssem" lights
// nothing while "ssem_target" lights the slab's edge nearest it; with the ball on screen the two
// agree to the rays' noise and the target's coarser pixels.
TEST_F(RendererTest, ScreenSpaceEmissiveTargetSeesEmittersBesideTheView) {
    Settings target = screenSpace();
    target.emissive.method = EmissiveMethod::SsemTarget;
    TestScene beside = glowingBallOverSlab({4.5f, 0.0f, 1.5f});
    const core::Frame off = render(beside, screenSpace());
    const core::Frame wide = render(beside, target);
    EXPECT_GT(wide.timingsMs.at("emissive"), 0.0);
    const Channels o{off.image}, w{wide.image};
    double offMost = 0.0, wideMost = 0.0;
    int floor = 0;
    for (int y = 0; y < off.image.height(); ++y)
        for (int x = 0; x < off.image.width(); ++x) {
            ASSERT_NE(o(x, y, "id"), 1.0f) << "the ball is on screen";
            if (o(x, y, "id") != 0.0f) continue;
            offMost = std::max(offMost, double(o(x, y, "irradiance.R")));
            wideMost = std::max(wideMost, double(w(x, y, "irradiance.R")));
            ++floor;
        }
    EXPECT_GT(floor, 5000);
    EXPECT_EQ(offMost, 0.0);
    EXPECT_GT(wideMost, 0.0);
    // A square target of the image's height (emissive.target_aspect = false) is narrower but
    // still reaches the ball here (measured: its largest E 0.99 times the aspect target's).
    Settings square = target;
    square.emissive.targetAspect = false;
    const Channels q{render(beside, square).image};
    double squareMost = 0.0;
    for (int y = 0; y < off.image.height(); ++y)
        for (int x = 0; x < off.image.width(); ++x)
            if (o(x, y, "id") == 0.0f)
                squareMost = std::max(squareMost, double(q(x, y, "irradiance.R")));
    EXPECT_GT(squareMost, 0.0);
    // Near the edge next to the ball: lit, within a factor 3 of the point lights' closed form
    // (measured: 0.44 of it; the target's pixels are twice as wide, and the blur mixes in the
    // edge's neighbours farther from the ball).
    const core::Camera camera(beside.scene.camera);
    const glm::dvec2 edge = camera.project({2.9, 0.0, 0.1});
    const double atEdge = w(int(edge.x), int(edge.y), "irradiance.R");
    const core::Frame points = render(beside, withMethod(EmissiveMethod::PointLights));
    const double edgeForm = Channels{points.image}(int(edge.x), int(edge.y), "irradiance.R");
    EXPECT_GT(atEdge, 0.0);
    EXPECT_GT(atEdge, edgeForm / 3.0);
    EXPECT_LT(atEdge, edgeForm * 3.0);

    // On screen: the mean over a ring 0.6 from the ball within a factor 1.5 of "ssem"'s
    // (measured: 0.93 of it).
    TestScene near = glowingBallOverSlab();
    const Channels a{render(near, screenSpace()).image}, b{render(near, target).image};
    auto meanAt = [&](const Channels& ch, double distance) {
        double sum = 0.0;
        int n = 0;
        for (int i = 0; i < 16; ++i) {
            const double t = 2.0 * std::numbers::pi * i / 16.0;
            const glm::dvec2 q =
                camera.project({-1.0 + distance * std::cos(t), distance * std::sin(t), 0.1});
            if (ch(int(q.x), int(q.y), "id") != 0.0f) continue;
            sum += ch(int(q.x), int(q.y), "irradiance.R");
            ++n;
        }
        return n > 0 ? sum / n : -1.0;
    };
    const double screen = meanAt(a, 0.6), targeted = meanAt(b, 0.6);
    EXPECT_GT(screen, 0.0);
    EXPECT_GT(targeted, screen / 1.5);
    EXPECT_LT(targeted, screen * 1.5);
}

// Without light.emissive_light (or with emissive.method = "none") no pass runs and the frame is
// the same, its irradiance channels 0.
TEST_F(RendererTest, WithoutEmissiveLightNothingChanges) {
    TestScene t = glowingBallOverSlab();
    t.scene.light.intensity = 2.0;
    t.scene.light.emissiveLight = false;
    const core::Frame plain = render(t, withMethod(EmissiveMethod::None));
    for (const EmissiveMethod method : {EmissiveMethod::PointLights, EmissiveMethod::Ssem}) {
        const core::Frame f = render(t, withMethod(method));
        EXPECT_EQ(f.timingsMs.at("emissive"), 0.0);
        ASSERT_EQ(f.image.channelNames(), plain.image.channelNames());
        for (std::size_t q = 0; q < f.image.pixelCount(); ++q)
            for (int k = 0; k < f.image.channelCount(); ++k)
                ASSERT_EQ(std::isnan(f.image.at(q, k)) ? 0.0f : f.image.at(q, k),
                          std::isnan(plain.image.at(q, k)) ? 0.0f : plain.image.at(q, k))
                    << f.image.channelNames()[k] << " " << toString(method);
        const int e = f.image.channelIndex("irradiance.R");
        for (std::size_t q = 0; q < f.image.pixelCount(); ++q)
            for (int k = 0; k < 3; ++k) ASSERT_EQ(f.image.at(q, e + k), 0.0f);
    }
    TestScene none = glowingBallOverSlab();
    none.scene.light.intensity = 2.0;
    const core::Frame off = render(none, withMethod(EmissiveMethod::None));
    EXPECT_EQ(off.timingsMs.at("emissive"), 0.0);
    for (std::size_t q = 0; q < off.image.pixelCount(); ++q)
        for (int k = 0; k < off.image.channelCount(); ++k)
            ASSERT_EQ(std::isnan(off.image.at(q, k)) ? 0.0f : off.image.at(q, k),
                      std::isnan(plain.image.at(q, k)) ? 0.0f : plain.image.at(q, k));
}

// A frame with the emissive light builds only programs that programVariants lists for it.
TEST_F(RendererTest, AnEmissiveFrameBuildsOnlyListedPrograms) {
    TestScene t = glowingBallOverSlab();
    t.finish();
    for (const EmissiveMethod method :
         {EmissiveMethod::PointLights, EmissiveMethod::Ssem, EmissiveMethod::SsemTarget}) {
        Settings s;
        s.emissive.method = method;
        Device fresh(context);
        Renderer(fresh, s).render({t.scene, t.particles, t.materials});
        std::vector<std::string> listed;
        for (const ProgramVariant& v : programVariants(s, true, true)) listed.push_back(v.name());
        for (const std::string& built : fresh.programNames())
            EXPECT_NE(std::find(listed.begin(), listed.end(), built), listed.end()) << built;
    }
}

}  // namespace
}  // namespace twinrender::realtime
