#include "raymarch/ao_hemisphere.h"

#include <gtest/gtest.h>

#include <cmath>

namespace twinrender::raymarch {
namespace {

// Whether the ray from the origin along unit d meets the sphere (centre c, radius a) within
// distance R.
bool hitsSphere(const glm::dvec3& d, const glm::dvec3& c, double a, double R) {
    const double b = glm::dot(d, c), disc = b * b - (glm::dot(c, c) - a * a);
    if (disc < 0.0) return false;
    const double t = b - std::sqrt(disc);
    return t > 0.0 && t <= R;
}

// The closed form: a sphere of radius a centred at height h on the normal of a point subtends
// the cone of half-angle alpha, sin(alpha) = a / h. With the cosine density cos(theta) / pi
// the cone holds the fraction
//   int_0^{2 pi} int_0^alpha cos(theta) sin(theta) dtheta dphi / pi = sin^2(alpha) = (a / h)^2,
// and every ray into it meets the sphere within sqrt(h^2 - a^2) (the tangent length), so with
// R at least that the occluded fraction is (a / h)^2.
TEST(AoHemisphere, ASphereAboveAPlaneOccludesTheClosedFormWithinTheStandardError) {
    const glm::dvec3 normal(0.0, 0.0, 1.0);
    for (const auto& [a, h] : {std::pair{0.5, 1.0}, std::pair{0.3, 1.5}, std::pair{0.9, 1.0}}) {
        const double R = std::sqrt(h * h - a * a) + 1e-9;
        const int side = 32;
        const auto dirs = aoDirections(normal, side, 7);
        int open = 0;
        for (const glm::dvec3& d : dirs) open += !hitsSphere(d, h * normal, a, R);
        const double estimate = static_cast<double>(open) / dirs.size();
        const double truth = 1.0 - (a / h) * (a / h);
        const double se = aoStandardError(truth, side * side);
        EXPECT_NEAR(estimate, truth, 3.0 * se) << "a=" << a << " h=" << h;
    }
}

TEST(AoHemisphere, AShorterRadiusSeesLessOfTheSphere) {
    const glm::dvec3 normal(0.0, 0.0, 1.0);
    const auto dirs = aoDirections(normal, 16, 1);
    int open = 0;
    for (const glm::dvec3& d : dirs) open += !hitsSphere(d, 1.0 * normal, 0.5, 0.4);
    EXPECT_EQ(open, 16 * 16);  // the sphere's nearest point is 0.5 away
}

TEST(AoHemisphere, DirectionsAreCosineWeightedUnitVectorsAboutTheNormal) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(-0.3, 0.8, -0.5));
    const auto dirs = aoDirections(n, 32, 11);
    double meanCos = 0.0;
    for (const glm::dvec3& d : dirs) {
        EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
        EXPECT_GE(glm::dot(d, n), 0.0);
        meanCos += glm::dot(d, n) / dirs.size();
    }
    EXPECT_NEAR(meanCos, 2.0 / 3.0, 1e-3);  // E[cos] under cos/pi is 2/3
}

TEST(AoHemisphere, TheSameSeedGivesTheSameDirections) {
    const glm::dvec3 n(0.0, 0.0, -1.0);
    EXPECT_EQ(aoDirections(n, 8, 42), aoDirections(n, 8, 42));
    EXPECT_NE(aoDirections(n, 8, 42), aoDirections(n, 8, 43));
}

TEST(AoHemisphere, TheStandardErrorIsTheBinomialBound) {
    EXPECT_DOUBLE_EQ(aoStandardError(0.5, 100), 0.05);
    EXPECT_DOUBLE_EQ(aoStandardError(1.0, 100), 0.0);
}

}  // namespace
}  // namespace twinrender::raymarch
