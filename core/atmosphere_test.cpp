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

// ---- the density falloff against answers computed another way ----------------------------

namespace {

// The shell of constantShell with a finite scale height: the density exp(-(|x| - R) / H) with
// |x| the distance from the shell's centre and R = 1 the inner radius (core/atmosphere.cpp,
// density), in scene units like the radii.
constexpr double SCALE_HEIGHT = 0.25;

tc::Atmosphere fallingShell() {
    tc::Atmosphere a = constantShell();
    a.scaleHeight = float(SCALE_HEIGHT);
    return a;
}

// The optical depth integral of the density along the ray, recovered from the transmittance
// exp(-sigma_t depth).
double opticalDepth(const tc::AtmosphereSample& s) {
    return -std::log(double(s.transmittance.g)) / SIGMA_T;
}

// The transmittance is a product of `steps` float exponentials, each within about an ulp: its
// relative error stays below steps x 1.2e-7 = 4e-6, the optical depth's (divided by
// sigma_t = 0.5) below 1e-5.
constexpr double FLOAT_DEPTH = 1e-5;

}  // namespace

// Straight up from the inner sphere, a path of length T has optical depth (per unit sigma_t)
// integral_0^T exp(-s / H) ds = H (1 - exp(-T / H)).
TEST(Atmosphere, OpticalDepthUpARadialRayMatchesTheClosedForm) {
    const tc::Atmosphere a = fallingShell();
    const tc::AtmosphereSun sun{.toSun = {0.0f, 0.0f, 1.0f}, .irradiance = glm::vec3(E)};
    // A direction along no axis, so that the height is |x| - R and not one coordinate.
    const glm::vec3 up = glm::vec3(2.0f, -1.0f, 2.0f) / 3.0f;
    const double length = 0.8;
    const tc::AtmosphereSample s = tc::integrateAtmosphere(a, sun, up, up, float(length));
    const double expected = SCALE_HEIGHT * (1.0 - std::exp(-length / SCALE_HEIGHT));
    // The midpoint rule on exp(-s / H) in steps of dt errs by the factor
    // (d/2) / sinh(d/2) = 1 - d^2/24 + ..., d = dt / H = 0.1 (a relative 4.2e-4, which the
    // code shows in full: a looser tolerance would hide a wrong step).
    const double d = length / a.steps / SCALE_HEIGHT;
    EXPECT_NEAR(opticalDepth(s), expected, expected * d * d / 24.0 + FLOAT_DEPTH);
}

// Up the same radial ray toward the sun, every point's light crosses the whole shell above the
// surface once (up to the point on the view ray, then on to the exit on the sun's path):
// T(s) T_sun(s) = exp(-sigma_t H (1 - exp(-thickness / H))) all along, so
// L_in = sigma_s p E exp(-sigma_t H (1 - exp(-thickness / H))) H (1 - exp(-T / H)).
// The sun's paths are integrated by their own quadrature: a wrong density there fails too.
TEST(Atmosphere, InScatterUpARadialRayTowardTheSunMatchesTheClosedForm) {
    const tc::Atmosphere a = fallingShell();
    const glm::vec3 up = glm::vec3(2.0f, -1.0f, 2.0f) / 3.0f;
    const tc::AtmosphereSun sun{.toSun = up, .irradiance = glm::vec3(E)};
    const double length = 0.8, thickness = 1.0;
    const tc::AtmosphereSample s = tc::integrateAtmosphere(a, sun, up, up, float(length));
    const double wholeShell = SCALE_HEIGHT * (1.0 - std::exp(-thickness / SCALE_HEIGHT));
    const double expected = SIGMA_S * ISOTROPIC * E * std::exp(-SIGMA_T * wholeShell) *
                            SCALE_HEIGHT * (1.0 - std::exp(-length / SCALE_HEIGHT));
    // Relative errors, each bounded as in the test above: the view ray's midpoint sum of the
    // density, d^2/24 (d = 0.1); the optical depths of the view and sun paths (sun steps up to
    // thickness / steps long, d_sun = 0.125), sigma_t wholeShell d_sun^2/24 in the product of
    // their transmittances; the midpoint's sun transmittance standing for a step's,
    // x^2/24 with x = sigma_t dt; float rounding, 1e-5.
    const double d = length / a.steps / SCALE_HEIGHT, dSun = thickness / a.steps / SCALE_HEIGHT;
    const double x = SIGMA_T * length / a.steps;
    const double relative =
        d * d / 24.0 + SIGMA_T * wholeShell * dSun * dSun / 24.0 + x * x / 24.0 + 1e-5;
    EXPECT_NEAR(s.inscatter.r, expected, expected * relative);
}

// A slanted ray from outside the shell down to the inner sphere (met at 37 degrees from its
// normal), against the optical depth integrated here in double precision by composite Simpson
// on 20,000 intervals (its error, (b - a) h^4 max|f''''| / 180, is below 1e-14).
TEST(Atmosphere, OpticalDepthAlongASlantedRayMatchesAFineQuadrature) {
    const tc::Atmosphere a = fallingShell();
    const tc::AtmosphereSun sun{.toSun = {0.0f, 0.0f, 1.0f}, .irradiance = glm::vec3(E)};
    // The ray (0, b, -3) + t (0, 0, 1): |x(t)| = sqrt(b^2 + (t - 3)^2), entering the shell
    // (radius 2) at t0 = 3 - sqrt(4 - b^2) and meeting the inner sphere at t1 = 3 - sqrt(1 - b^2).
    const double b = 0.6;
    const double t0 = 3.0 - std::sqrt(4.0 - b * b), t1 = 3.0 - std::sqrt(1.0 - b * b);
    const auto radius = [&](double t) { return std::sqrt(b * b + (t - 3.0) * (t - 3.0)); };
    const auto density = [&](double t) { return std::exp(-(radius(t) - 1.0) / SCALE_HEIGHT); };
    const auto slope = [&](double t) {  // d density / dt
        return -density(t) / SCALE_HEIGHT * (t - 3.0) / radius(t);
    };
    const int intervals = 20000;
    const double h = (t1 - t0) / intervals;
    double sum = density(t0) + density(t1);
    for (int i = 1; i < intervals; ++i) sum += (i % 2 ? 4.0 : 2.0) * density(t0 + i * h);
    const double expected = sum * h / 3.0;

    const tc::AtmosphereSample s =
        tc::integrateAtmosphere(a, sun, {0.0f, float(b), -3.0f}, {0.0f, 0.0f, 1.0f}, float(t1));
    // The midpoint rule's error is -(dt^2/24) (f'(t1) - f'(t0)) to leading order
    // (Euler-Maclaurin); the next term, (7 dt^4/5760) (f'''(t1) - f'''(t0)), is below 1 % of it
    // at dt / H = 0.14. A quarter more than the leading term, and the float rounding.
    const double dt = (t1 - t0) / a.steps;
    const double leading = dt * dt / 24.0 * std::abs(slope(t1) - slope(t0));
    EXPECT_NEAR(opticalDepth(s), expected, 1.25 * leading + FLOAT_DEPTH);
}
