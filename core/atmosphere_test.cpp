#include "core/atmosphere.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/body_sphere.h"
#include "core/sph_kernel.h"

namespace tc = twinrender::core;

namespace {

// A shell of constant density (a scale height far beyond its thickness: exp(-h / H) rounds to
// 1 in floats) between radii 1 and 2, isotropic, sigma_t = 0.5 in every channel.
tc::Atmosphere constantShell() {
    return {.body = 0,
            .centre = glm::dvec3(0.0),
            .innerRadius = 1.0f,
            .outerRadius = 2.0f,
            .scaleHeight = 1e30f,
            .scattering = glm::vec3(0.3f),
            .absorption = glm::vec3(0.2f),
            .phaseG = 0.0f,
            .steps = 32};
}

constexpr float SIGMA_S = 0.3f, SIGMA_T = 0.5f, E = 2.0f;
const float ISOTROPIC = 1.0f / (4.0f * 3.14159265358979f);

}  // namespace

// Looking at the sun along a chord of length L that misses the inner sphere, every point's sun
// path leaves the shell where the view ray does: T(t) T_sun(x) = exp(-sigma_t L) all along, so
// L_in = sigma_s p E exp(-sigma_t L) L.
TEST(Atmosphere, InScatterTowardTheSunMatchesTheClosedForm) {
    const tc::Atmosphere a = constantShell();
    const tc::AtmosphereSun sun{.toSun = {0.0f, 0.0f, 1.0f}, .irradiance = glm::vec3(E)};
    const float length = 2.0f * std::sqrt(4.0f - 1.5f * 1.5f);
    const tc::AtmosphereSample s =
        tc::integrateAtmosphere(a, sun, {0.0f, 1.5f, -5.0f}, {0.0f, 0.0f, 1.0f}, INFINITY);
    const float expected = SIGMA_S * ISOTROPIC * E * std::exp(-SIGMA_T * length) * length;
    // The midpoint's sun transmittance stands for a step's: relative error
    // sinh(x/2)/(x/2) - 1 ~ x^2/24, x = sigma_t dt; float rounding is below 1e-5.
    const float x = SIGMA_T * length / float(a.steps);
    EXPECT_NEAR(s.inscatter.r, expected, expected * (x * x / 24.0f + 1e-5f));
    EXPECT_NEAR(s.transmittance.g, std::exp(-SIGMA_T * length), 1e-5f);
}

// Looking away from the sun, a point s past the entry sees the sun through the same s:
// T T_sun = exp(-2 sigma_t s), so L_in = sigma_s p E (1 - exp(-2 sigma_t L)) / (2 sigma_t); the
// end point (a surface) cuts the segment at L.
TEST(Atmosphere, InScatterAwayFromTheSunUpToASurfaceMatchesTheClosedForm) {
    const tc::Atmosphere a = constantShell();
    const tc::AtmosphereSun sun{.toSun = {0.0f, 0.0f, -1.0f}, .irradiance = glm::vec3(E)};
    const glm::vec3 origin{0.0f, 1.5f, -5.0f};
    const float entry = 5.0f - std::sqrt(4.0f - 1.5f * 1.5f), length = 1.2f;
    const tc::AtmosphereSample s =
        tc::integrateAtmosphere(a, sun, origin, {0.0f, 0.0f, 1.0f}, entry + length);
    const float expected =
        SIGMA_S * ISOTROPIC * E * (1.0f - std::exp(-2.0f * SIGMA_T * length)) / (2.0f * SIGMA_T);
    // Here the midpoint's sun transmittance errs by 1 / cosh(x/2) - 1 ~ -x^2/8 a step.
    const float x = SIGMA_T * length / float(a.steps);
    EXPECT_NEAR(s.inscatter.b, expected, expected * (x * x / 8.0f + 1e-5f));
    EXPECT_NEAR(s.transmittance.r, std::exp(-SIGMA_T * length), 1e-5f);
}

// From inside the shell, looking away from the sun straight behind the inner sphere: every
// point of the segment is in its shadow (no in-scatter), and the segment starts at the camera.
TEST(Atmosphere, TheInnerSphereShadowsAndTheSegmentStartsAtTheCamera) {
    const tc::Atmosphere a = constantShell();
    const tc::AtmosphereSun sun{.toSun = {0.0f, 0.0f, 1.0f}, .irradiance = glm::vec3(E)};
    const tc::AtmosphereSample s =
        tc::integrateAtmosphere(a, sun, {0.0f, 0.0f, -1.5f}, {0.0f, 0.0f, -1.0f}, INFINITY);
    EXPECT_EQ(s.inscatter, glm::vec3(0.0f));
    EXPECT_NEAR(s.transmittance.r, std::exp(-SIGMA_T * 0.5f), 1e-6f);
}

// Forward scattering (g > 0) brightens the view toward the sun by the Henyey-Greenstein phase
// at cos(theta) = 1, (1 - g^2) / (4 pi (1 - g)^3), against the isotropic 1 / (4 pi).
TEST(Atmosphere, ThePhaseFunctionScalesTheInScatter) {
    tc::Atmosphere a = constantShell();
    const tc::AtmosphereSun sun{.toSun = {0.0f, 0.0f, 1.0f}, .irradiance = glm::vec3(E)};
    const glm::vec3 origin{0.0f, 1.5f, -5.0f}, direction{0.0f, 0.0f, 1.0f};
    const float isotropic =
        tc::integrateAtmosphere(a, sun, origin, direction, INFINITY).inscatter.r;
    a.phaseG = 0.5f;
    const float forward = tc::integrateAtmosphere(a, sun, origin, direction, INFINITY).inscatter.r;
    EXPECT_NEAR(forward / isotropic, (1.0f - 0.25f) / (0.125f), 1e-4f);
}

// A ray that misses the shell, or ends before it, passes unchanged.
TEST(Atmosphere, OutsideTheShellNothingChanges) {
    const tc::Atmosphere a = constantShell();
    const tc::AtmosphereSun sun{.toSun = {0.0f, 0.0f, 1.0f}, .irradiance = glm::vec3(E)};
    const tc::AtmosphereSample miss =
        tc::integrateAtmosphere(a, sun, {0.0f, 2.5f, -5.0f}, {0.0f, 0.0f, 1.0f}, INFINITY);
    EXPECT_EQ(miss.transmittance, glm::vec3(1.0f));
    EXPECT_EQ(miss.inscatter, glm::vec3(0.0f));
    const tc::AtmosphereSample before =
        tc::integrateAtmosphere(a, sun, {0.0f, 0.0f, -5.0f}, {0.0f, 0.0f, 1.0f}, 2.0f);
    EXPECT_EQ(before.inscatter, glm::vec3(0.0f));
}

TEST(Atmosphere, SphereEntryIsTheNearIntersectionAhead) {
    EXPECT_NEAR(tc::sphereEntry({0.0f, 0.0f, -5.0f}, {0.0f, 0.0f, 1.0f}, 1.0f), 4.0f, 1e-6f);
    EXPECT_NEAR(tc::sphereEntry({0.0f, 0.6f, -5.0f}, {0.0f, 0.0f, 1.0f}, 1.0f), 4.2f, 1e-5f);
    EXPECT_TRUE(std::isinf(tc::sphereEntry({0.0f, 1.5f, -5.0f}, {0.0f, 0.0f, 1.0f}, 1.0f)));
    EXPECT_TRUE(std::isinf(tc::sphereEntry({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 1.0f}, 1.0f)));
}

// One particle's colour field is a sphere of the radius where v W(r, h) = level: the inner
// sphere a body's atmosphere takes when atmosphere.radius is not given.
TEST(Atmosphere, TheInnerRadiusIsTheLevelSetsOfOneParticle) {
    tc::ParticleSet ps;
    ps.resize(1);
    ps.position[0] = {0.5f, -0.2f, 0.1f};
    ps.h[0] = 0.4f;
    ps.volume[0] = 0.02f;
    const tc::BodyInfo body{.name = "one", .begin = 0, .end = 1};
    const double level = 0.13;
    double lo = 0.0, hi = 0.8;
    for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (0.02 * tc::m4Kernel(mid, 0.4) > level ? lo : hi) = mid;
    }
    // Bisection to 1e-7 of the field's reach (0.8) in each direction, the field in floats.
    EXPECT_NEAR(tc::levelSetRadius(ps, body, level), lo, 1e-6);
    EXPECT_EQ(tc::levelSetRadius(ps, body, 1e9), 0.0);
}
