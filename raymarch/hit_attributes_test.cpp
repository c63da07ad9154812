#include "raymarch/hit_attributes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <vector>

#include "raymarch/testing/ray_field_testing.h"
#include "raymarch/vector_loops.h"

namespace tr = twinrender;
namespace rt = twinrender::raymarch::testing;

TEST(HitAttributes, SurfacePointIsTheGradientAndWeightsOfTheField) {
    const tr::core::ParticleSet ps = rt::particlesAroundXAxis();
    const glm::dvec3 origin(-2.0, 0.1, 0.05),
        direction = glm::normalize(glm::dvec3(1.0, 0.1, -0.05));
    tr::raymarch::RayField field;
    tr::raymarch::ParticleBatch batch;
    rt::buildField(field, batch, ps, origin, direction, 1.0, 4.0);
    std::vector<float> weights;
    for (double t = 1.5; t < 3.5; t += 0.25) {
        const glm::dvec3 p = origin + t * direction;
        const auto point = tr::raymarch::surfacePoint(field, t, weights);
        ASSERT_EQ(weights.size() % tr::raymarch::LANES, 0u);
        // The weights sum to phi; the gradient is phi's (central differences, in double).
        double sum = 0.0;
        for (float w : weights) sum += w;
        const double phi = rt::fieldInDouble(ps, p);
        EXPECT_NEAR(sum, phi, 1e-5 * phi + 1e-9) << t;
        const double e = 1e-4;
        for (int k = 0; k < 3; ++k) {
            glm::dvec3 step(0.0);
            step[k] = e;
            const double derivative =
                (rt::fieldInDouble(ps, p + step) - rt::fieldInDouble(ps, p - step)) / (2.0 * e);
            EXPECT_NEAR(point.gradient[k], derivative, 1e-3 * glm::length(point.gradient) + 1e-7)
                << t << " axis " << k;
        }
        // The smallest h among the particles whose support contains p.
        double hMin = 0.0;
        for (std::size_t i = 0; i < ps.size(); ++i)
            if (glm::length(p - glm::dvec3(ps.position[i])) < 2.0 * ps.h[i])
                hMin = hMin > 0.0 ? std::min(hMin, double(ps.h[i])) : double(ps.h[i]);
        EXPECT_NEAR(point.hMin, hMin, 1e-6) << t;
    }
}

TEST(HitAttributes, AverageUnwrapsUAtTheSeam) {
    const tr::core::ParticleSet ps = rt::particlesAroundXAxis();
    std::vector<tr::raymarch::HitAttributes> attributes(ps.size());
    for (std::size_t i = 0; i < ps.size(); ++i)
        attributes[i] = {i % 2 ? 0.02f : 0.97f, 0.1f * i, 1.0f, 2.0f, 3.0f};
    tr::raymarch::RayField field;
    tr::raymarch::ParticleBatch batch;
    rt::buildField(field, batch, ps, {-2.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, 0.0, 4.0, &attributes);
    // Two particles of equal weight across the seam: u averages to the seam, not to 0.5.
    std::vector<float> weights(batch.size(), 0.0f);
    weights[0] = weights[1] = 0.5f;
    tr::raymarch::HitAttributes out{};
    ASSERT_TRUE(tr::raymarch::averageAttributes(batch, weights.data(), weights.size(), out));
    EXPECT_NEAR(std::min(out.u, 1.0f - out.u), 0.005f, 1e-6f);
    EXPECT_NEAR(out.v, 0.05f, 1e-6f);
    EXPECT_FLOAT_EQ(out.r, 1.0f);
    EXPECT_FLOAT_EQ(out.b, 3.0f);
    // No positive weight: nothing to average.
    std::fill(weights.begin(), weights.end(), 0.0f);
    EXPECT_FALSE(tr::raymarch::averageAttributes(batch, weights.data(), weights.size(), out));
}
