// The atmosphere pass (realtime.atmosphere.*) on llvmpipe: a ball of particles with an
// atmosphere, seen whole. Each end point gives core's model (core/atmosphere.h) ended where it
// says, pixel for pixel: the analytic sphere's hit, the impostor depth, the filtered depth, and
// the blend between the last two; an atmosphere that neither scatters nor absorbs changes
// nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>

#include "core/atmosphere.h"
#include "core/camera.h"
#include "realtime/passes.h"
#include "realtime/program_variants.h"
#include "realtime/testing/gl_test_scene.h"

namespace twinrender::realtime {
namespace {

using testing::Channels;
using testing::quiet;
using testing::RendererTest;
using testing::TestScene;

// A ball of radius 1 (particles 0.1 apart, body 0) at the origin, seen from (0, 0, 10), lit
// from the upper left, with an atmosphere 0.3 thick about its surface sphere.
TestScene ballWithAtmosphere(glm::dvec3 scattering = {1.0, 2.0, 4.0}) {
    TestScene t;
    t.scene.light.direction = glm::normalize(glm::dvec3(-1.0, -0.3, -0.5));
    for (int z = -10; z <= 10; ++z)
        for (int y = -10; y <= 10; ++y)
            for (int x = -10; x <= 10; ++x)
                if (x * x + y * y + z * z <= 100)
                    t.add(0, glm::vec3(x, y, z) * 0.1f, 0.13f, {0.5f, 0.5f},
                          glm::normalize(glm::vec3(x, y, z) + glm::vec3(0.0f, 0.0f, 0.01f)));
    t.particles.bodies[0].end = t.particles.particles.size();
    core::BodyDesc body;
    body.atmosphere = core::AtmosphereDesc{.thickness = 0.3,
                                           .scaleHeight = 0.1,
                                           .scattering = scattering,
                                           .absorption = 0.2 * scattering,
                                           .phaseG = 0.3,
                                           .radius = std::nullopt,
                                           .steps = 16};
    t.scene.bodies.push_back(body);
    return t;
}

Settings withEndPoint(AtmosphereEndPoint endPoint) {
    Settings s = quiet();
    s.atmosphere.endPoint = endPoint;
    return s;
}

// Compares every pixel's in-scatter with the model ended at end(x, y, ray) (INFINITY: the
// shell's exit), away from the inner sphere's rim (within `rim` scene units of it), where a
// pixel centre grazes the sphere; returns the pixels compared.
template <typename End>
int expectTheModel(const TestScene& t, const core::Frame& f, double rim, End end) {
    const auto atmosphere =
        core::sceneAtmosphere(t.scene, t.particles, quiet().particles.surfaceLevel);
    EXPECT_TRUE(atmosphere);
    if (!atmosphere) return 0;
    const core::AtmosphereSun sun = core::atmosphereSun(t.scene.light);
    const core::Camera camera(t.scene.camera);
    const Channels c{f.image};
    int compared = 0;
    for (int y = 0; y < f.image.height(); ++y)
        for (int x = 0; x < f.image.width(); ++x) {
            const core::Ray ray = camera.ray(x + 0.5, y + 0.5);
            const glm::dvec3 o = ray.origin - atmosphere->centre;
            const glm::dvec3 closest = o - glm::dot(o, ray.direction) * ray.direction;
            if (std::abs(glm::length(closest) - atmosphere->innerRadius) < rim) continue;
            const float e = end(x, y, ray, *atmosphere);
            const glm::vec3 expected = core::integrateAtmosphere(*atmosphere, sun, glm::vec3(o),
                                                                 glm::vec3(ray.direction), e)
                                           .inscatter;
            const char* names[] = {"inscatter.R", "inscatter.G", "inscatter.B"};
            // The shader runs the same float code from the ray it rebuilds for the pixel centre:
            // exp and sqrt to a few ulps and the direction to ~1e-6, summed over 16 x 16 steps;
            // 2e-3 relative with room, and an absolute floor for the dim limb.
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(c(x, y, names[k]), expected[k], 2e-3f * expected[k] + 2e-5f)
                    << x << "," << y << " " << names[k];
            compared += expected.b > 0.0f;
        }
    return compared;
}

// The end point at the depth a frame shows (its Z, eye depth, along the pixel's ray).
auto atDepth(const core::Frame& f, const core::Camera& camera) {
    return [&f, &camera](int x, int y, const core::Ray& ray, const core::Atmosphere&) {
        const float z = Channels{f.image}(x, y, "Z");
        return std::isinf(z) ? INFINITY : float(z / glm::dot(ray.direction, camera.forward()));
    };
}

// The analytic end point: the model ended at the inner sphere's entry, the shell's exit where
// the ray misses it; on the sky the beauty is the in-scatter alone.
TEST_F(RendererTest, TheSphereEndPointIsTheModelAtTheAnalyticSphere) {
    TestScene t = ballWithAtmosphere();
    const core::Frame f = render(t, withEndPoint(AtmosphereEndPoint::Sphere));
    EXPECT_GT(f.timingsMs.at("atmosphere"), 0.0);
    const int compared =
        expectTheModel(t, f, 0.02, [](int, int, const core::Ray& ray, const core::Atmosphere& a) {
            return core::sphereEntry(glm::vec3(ray.origin - a.centre), glm::vec3(ray.direction),
                                     a.innerRadius);
        });
    EXPECT_GT(compared, 1000);
    const Channels c{f.image};
    // A sky pixel inside the shell, off the ball (its inner sphere 18 pixels in radius, its outer
    // 23): beauty = in-scatter.
    const int x = testing::WIDTH / 2 + 20, y = testing::HEIGHT / 2;
    ASSERT_LT(c(x, y, "id"), 0.0f);
    EXPECT_GT(c(x, y, "inscatter.B"), 0.0f);
    EXPECT_EQ(c(x, y, "B"), c(x, y, "inscatter.B"));
}

// The depth end points: the model ended at the depth seen (the frame's Z, eye depth, along the
// pixel's ray); impostor and filtered read the same depth when no depth filter runs, and blend
// is the filtered depth nearer than blend_near and the sphere beyond blend_far.
TEST_F(RendererTest, TheDepthEndPointsAreTheModelAtTheDepthSeen) {
    TestScene t = ballWithAtmosphere();
    const core::Camera camera(t.scene.camera);
    // The impostors' depth steps at their silhouettes: 0.05 scene units from the sphere's rim.
    for (AtmosphereEndPoint endPoint :
         {AtmosphereEndPoint::Impostor, AtmosphereEndPoint::Filtered}) {
        const core::Frame f = render(t, withEndPoint(endPoint));
        EXPECT_GT(expectTheModel(t, f, 0.05, atDepth(f, camera)), 1000) << toString(endPoint);
    }
    Settings near = withEndPoint(AtmosphereEndPoint::Blend);
    near.atmosphere.blendNear = 100.0;
    near.atmosphere.blendFar = 200.0;
    const core::Frame depth = render(t, near);
    EXPECT_GT(expectTheModel(t, depth, 0.05, atDepth(depth, camera)), 1000);
    Settings far = near;
    far.atmosphere.blendNear = 0.0;
    far.atmosphere.blendFar = 1.0;
    const core::Frame sphere = render(t, far);
    const core::Frame analytic = render(t, withEndPoint(AtmosphereEndPoint::Sphere));
    const std::size_t n = sphere.image.pixels().size();
    EXPECT_EQ(std::memcmp(sphere.image.pixels().data(), analytic.image.pixels().data(),
                          n * sizeof(float)),
              0);
}

// The filtered end point reads what a depth filter wrote: its in-scatter follows the filtered
// depth, not the impostors'.
TEST_F(RendererTest, TheFilteredEndPointFollowsTheDepthFilter) {
    TestScene t = ballWithAtmosphere();
    Settings filtered = withEndPoint(AtmosphereEndPoint::Filtered);
    filtered.surface.method = SurfaceMethod::Bilateral;
    Settings impostor = filtered;
    impostor.atmosphere.endPoint = AtmosphereEndPoint::Impostor;
    const core::Frame a = render(t, filtered), b = render(t, impostor);
    const core::Camera camera(t.scene.camera);
    EXPECT_GT(expectTheModel(t, a, 0.05, atDepth(a, camera)), 1000);
    int differ = 0;
    const Channels ca{a.image}, cb{b.image};
    for (int y = 0; y < a.image.height(); ++y)
        for (int x = 0; x < a.image.width(); ++x)
            differ += ca(x, y, "inscatter.B") != cb(x, y, "inscatter.B");
    EXPECT_GT(differ, 100);
}

// Without an atmosphere the pass does not run and the in-scatter is 0; an atmosphere that
// neither scatters nor absorbs leaves every channel as it was, bit for bit.
TEST_F(RendererTest, AnEmptyAtmosphereChangesNothing) {
    TestScene with = ballWithAtmosphere(glm::dvec3(0.0));
    TestScene without = ballWithAtmosphere();
    without.scene.bodies.clear();
    const core::Frame a = render(with, quiet()), b = render(without, quiet());
    EXPECT_EQ(b.timingsMs.at("atmosphere"), 0.0);
    ASSERT_EQ(a.image.pixels().size(), b.image.pixels().size());
    EXPECT_EQ(std::memcmp(a.image.pixels().data(), b.image.pixels().data(),
                          a.image.pixels().size() * sizeof(float)),
              0);
    EXPECT_EQ(std::memcmp(a.display.pixels().data(), b.display.pixels().data(),
                          a.display.pixels().size() * sizeof(float)),
              0);
}

// Every end point's program is among the variants a frame with an atmosphere compiles.
TEST(AtmosphereVariants, EachEndPointHasItsProgram) {
    for (AtmosphereEndPoint endPoint : {AtmosphereEndPoint::Impostor, AtmosphereEndPoint::Filtered,
                                        AtmosphereEndPoint::Sphere, AtmosphereEndPoint::Blend}) {
        Settings s;
        s.atmosphere.endPoint = endPoint;
        bool found = false;
        for (const ProgramVariant& v : programVariants(s, false, false, true))
            found = found || (v.fragment == "atmosphere.frag" &&
                              v.defines == atmosphereDefines(s.atmosphere));
        EXPECT_TRUE(found) << toString(endPoint);
        bool inAll = false;
        for (const ProgramVariant& v : allProgramVariants())
            inAll = inAll || (v.fragment == "atmosphere.frag" &&
                              v.defines == atmosphereDefines(s.atmosphere));
        EXPECT_TRUE(inAll) << toString(endPoint);
    }
}

}  // namespace
}  // namespace twinrender::realtime
