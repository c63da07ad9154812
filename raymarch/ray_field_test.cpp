#include "raymarch/ray_field.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "raymarch/field_sample.h"
#include "raymarch/testing/ray_field_testing.h"

namespace tr = twinrender;
namespace rt = twinrender::raymarch::testing;

TEST(RayField, BuildFromABatchAgreesWithTheFieldSummedInDouble) {
    const tr::core::ParticleSet ps = rt::particlesAroundXAxis();
    const glm::dvec3 origin(-3.0, 0.2, -0.1),
        direction = glm::normalize(glm::dvec3(1.0, -0.05, 0.02));
    const double tMin = 3.0, tMax = 7.0;
    tr::raymarch::RayField field;
    tr::raymarch::ParticleBatch batch;
    rt::buildField(field, batch, ps, origin, direction, tMin, tMax);

    // The candidates whose support interval overlaps [tMin, tMax], and where the first begins.
    std::size_t overlapping = 0;
    double start = INFINITY;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        const glm::dvec3 w = glm::dvec3(ps.position[i]) - origin;
        const double tc = glm::dot(w, direction);
        const glm::dvec3 off = w - tc * direction;
        const double chord2 = 4.0 * double(ps.h[i]) * ps.h[i] - glm::dot(off, off);
        if (chord2 <= 0.0) continue;
        const double half = std::sqrt(chord2);
        if (tc + half <= tMin || tc - half >= tMax) continue;
        ++overlapping;
        start = std::min(start, tc - half);
    }
    ASSERT_GT(overlapping, 5u);
    EXPECT_EQ(field.candidates(), overlapping);
    EXPECT_NEAR(field.supportStart(), start, 1e-4);

    for (double t = tMin; t <= tMax; t += 0.05) {
        const auto sample = tr::raymarch::sampleValue(field, t);
        EXPECT_NEAR(sample.value, rt::fieldInDouble(ps, origin + t * direction),
                    1e-5 * field.peakSum())
            << t;
        const double dt = 1e-4;
        const double slope = (rt::fieldInDouble(ps, origin + (t + dt) * direction) -
                              rt::fieldInDouble(ps, origin + (t - dt) * direction)) /
                             (2.0 * dt);
        EXPECT_NEAR(sample.slope, slope, 1e-4 * field.peakSum()) << t;
        // phi never exceeds the sum of the peaks.
        EXPECT_LE(sample.value, field.peakSum()) << t;
    }
}
