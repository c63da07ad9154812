#include "realtime/octahedral.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <random>

namespace twinrender::realtime {
namespace {

TEST(Octahedral, RoundTripsUnitVectors) {
    std::mt19937 rng(1);
    std::normal_distribution<float> g;
    for (int i = 0; i < 10000; ++i) {
        const glm::vec3 n = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
        const glm::vec2 e = octEncode(n);
        EXPECT_LE(std::max(std::abs(e.x), std::abs(e.y)), 1.0f);  // inside the unit square
        EXPECT_GT(glm::dot(octDecode(e), n), 1.0f - 1e-6f) << n.x << " " << n.y << " " << n.z;
    }
    for (const glm::vec3 n :
         {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0), glm::vec3(0, -1, 0)})
        EXPECT_GT(glm::dot(octDecode(octEncode(n)), n), 1.0f - 1e-6f);
}

}  // namespace
}  // namespace twinrender::realtime
