#include "realtime/light_frustum.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace twinrender::realtime {
namespace {

TEST(LightFrustum, HoldsTheBoundsWithUniformTexels) {
    const glm::dvec3 lo(-1.0, -2.0, -0.5), hi(3.0, 1.0, 0.5), origin(0.0, -6.0, 1.5);
    for (const glm::dvec3& direction :
         {glm::dvec3(-1.0, 0.4, -0.3), glm::dvec3(0.0, 0.0, -1.0), glm::dvec3(1.0, 0.0, 0.0)}) {
        const LightFrustum f = fitLightFrustum(lo, hi, origin, direction, 1024);
        for (int corner = 0; corner < 8; ++corner) {
            const glm::dvec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                               (corner & 4) ? hi.z : lo.z);
            const glm::dvec4 l = f.view * glm::dvec4(p - origin, 1.0);
            const glm::dvec4 c = f.clip * l;
            EXPECT_LT(std::abs(c.x), 1.0);
            EXPECT_LT(std::abs(c.y), 1.0);
            EXPECT_GT(-l.z, f.nearDepth);
            EXPECT_LT(-l.z, f.farDepth);
        }
        // Depth grows along the light's direction of travel.
        const glm::dvec3 centre = 0.5 * (lo + hi) - origin;
        const double d0 = -(f.view * glm::dvec4(centre, 1.0)).z;
        const double d1 = -(f.view * glm::dvec4(centre + glm::normalize(direction), 1.0)).z;
        EXPECT_NEAR(d1 - d0, 1.0, 1e-9);
        EXPECT_GT(f.texelSize, 0.0);
    }
}

}  // namespace
}  // namespace twinrender::realtime
