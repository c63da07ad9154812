#include "raymarch/sun_disc.h"

#include <gtest/gtest.h>

#include <cmath>

namespace twinrender::raymarch {
namespace {

TEST(SunDisc, APointSunIsTheLightDirectionAlone) {
    const glm::dvec3 l = glm::normalize(glm::dvec3(1.0, -0.4, 0.3));
    const auto d = sunDirections(l, 0.0, 16);
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0], l);
}

TEST(SunDisc, DirectionsFillTheConeEvenlyAboutTheLight) {
    for (const glm::dvec3 l : {glm::dvec3(0.0, 0.0, 1.0), glm::dvec3(0.0, 0.0, -1.0),
                               glm::normalize(glm::dvec3(-1.0, 0.4, -0.3))}) {
        const double radius = 5.0;
        const auto d = sunDirections(l, radius, 64);
        ASSERT_EQ(d.size(), 64u);
        glm::dvec3 mean(0.0);
        int inner = 0;  // inside the cone of half the solid angle
        const double halfCap = 1.0 - 0.5 * (1.0 - std::cos(glm::radians(radius)));
        for (const glm::dvec3& x : d) {
            EXPECT_NEAR(glm::length(x), 1.0, 1e-12);
            EXPECT_LE(glm::degrees(std::acos(std::min(1.0, glm::dot(x, l)))), radius + 1e-9);
            inner += glm::dot(x, l) > halfCap;
            mean += x;
        }
        EXPECT_EQ(inner, 32);
        // The spiral's centroid lies on the axis to within a small fraction of the radius.
        const double offDeg =
            glm::degrees(std::acos(std::min(1.0, glm::dot(glm::normalize(mean), l))));
        EXPECT_LT(offDeg, 0.05 * radius);
    }
}

}  // namespace
}  // namespace twinrender::raymarch
