#include "realtime/field_normal.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "realtime/impostor_radius.h"

namespace twinrender::realtime {
namespace {

glm::dvec3 modelNormal(const FieldNormal& f, const glm::dvec3& offset) {
    const glm::dvec3 d(f.diagonal), o(f.offDiagonal);
    const glm::dvec3 change(d.x * offset.x + o.x * offset.y + o.y * offset.z,
                            o.x * offset.x + d.y * offset.y + o.z * offset.z,
                            o.y * offset.x + o.z * offset.y + d.z * offset.z);
    return glm::normalize(glm::dvec3(f.outward) + change);
}

double degreesBetween(const glm::dvec3& a, const glm::dvec3& b) {
    const double c = glm::dot(glm::normalize(a), glm::normalize(b));
    return glm::degrees(std::acos(std::clamp(c, -1.0, 1.0)));
}

// One particle: the field is its own kernel, whose normal is the sphere's. The model is exact
// at the top point and follows the sphere to first order around it.
TEST(FieldNormal, FollowsALoneParticlesSphere) {
    core::ParticleSet ps;
    ps.resize(1);
    ps.position[0] = {1.0f, 2.0f, 3.0f};
    ps.h[0] = 0.5f;
    ps.volume[0] = 0.05f;
    ps.normal[0] = glm::normalize(glm::vec3(0.0f, 0.6f, 0.8f));
    const double scale = 0.9, r = scale * 0.5;
    const std::vector<FieldNormal> f = fieldNormals(ps, fixedRadii(ps, scale));
    ASSERT_EQ(f.size(), 1u);
    const glm::dvec3 n(ps.normal[0]);
    EXPECT_LT(degreesBetween(modelNormal(f[0], r * n), n), 1e-3);
    const glm::dvec3 across = glm::normalize(glm::cross(n, glm::dvec3(1, 0, 0)));
    for (double angle : {0.05, 0.1}) {
        const glm::dvec3 sphere = std::cos(angle) * n + std::sin(angle) * across;
        EXPECT_LT(degreesBetween(modelNormal(f[0], r * sphere), sphere), 0.1 * glm::degrees(angle))
            << angle;
    }
}

// A flat square lattice: at the top layer's impostors the model points up, and only the
// indices asked for are modelled (the field still sums every particle).
TEST(FieldNormal, PointsOutOfAFlatLatticeForTheChosenParticles) {
    core::ParticleSet ps;
    const int n = 9;
    const float s = 0.1f;
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                ps.position.emplace_back(x * s, y * s, z * s);
                ps.h.push_back(1.3f * s);
                ps.volume.push_back(s * s * s);
                ps.normal.emplace_back(0.0f, 0.0f, 1.0f);
            }
    const std::uint32_t centreTop = static_cast<std::uint32_t>((2 * n + 4) * n + 4);
    const std::uint32_t chosen[] = {centreTop};
    const std::vector<FieldNormal> f = fieldNormals(ps, fixedRadii(ps, 0.9), chosen);
    ASSERT_EQ(f.size(), 1u);
    const double r = 0.9 * 1.3 * s;
    EXPECT_LT(degreesBetween(modelNormal(f[0], {0.0, 0.0, r}), {0.0, 0.0, 1.0}), 1e-3);
    // Symmetric neighbours: a point off the top tilts the normal the way the bump does.
    const glm::dvec3 side = modelNormal(f[0], {0.3 * r, 0.0, r * std::sqrt(1.0 - 0.09)});
    EXPECT_GT(side.x, 0.0);
    EXPECT_NEAR(side.y, 0.0, 1e-6);
}

TEST(FieldNormal, TheCacheReusesItsAnswerOnlyForTheSameInputs) {
    core::ParticleSet ps;
    ps.resize(3);
    ps.position = {{0.0f, 0.0f, 0.0f}, {0.1f, 0.0f, 0.0f}, {0.0f, 0.1f, 0.0f}};
    ps.h = {0.13f, 0.13f, 0.13f};
    ps.volume = {0.001f, 0.001f, 0.001f};
    ps.normal = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    FieldNormalCache cache;
    const std::uint32_t some[] = {0, 2};
    const auto first = cache.normals(ps, fixedRadii(ps, 0.9), some);
    EXPECT_FALSE(cache.reused());
    ASSERT_EQ(first.size(), 2u);
    EXPECT_EQ(cache.normals(ps, fixedRadii(ps, 0.9), some)[1].outward, first[1].outward);
    EXPECT_TRUE(cache.reused());
    EXPECT_EQ(cache.normals(ps, fixedRadii(ps, 0.9), {}).size(), 3u);
    EXPECT_FALSE(cache.reused());
    ps.volume[1] = 0.002f;
    cache.normals(ps, fixedRadii(ps, 0.9), {});
    EXPECT_FALSE(cache.reused());
    cache.normals(ps, fixedRadii(ps, 0.8), {});
    EXPECT_FALSE(cache.reused());
    cache.normals(ps, fixedRadii(ps, 0.8), {});
    EXPECT_TRUE(cache.reused());
}

}  // namespace
}  // namespace twinrender::realtime
