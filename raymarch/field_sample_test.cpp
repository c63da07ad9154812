#include "raymarch/field_sample.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/sph_kernel.h"
#include "raymarch/testing/ray_field_testing.h"

namespace tr = twinrender;
namespace rt = twinrender::raymarch::testing;

TEST(FieldSample, RemainingBoundIsAnUpperBound) {
    std::vector<glm::dvec3> centers;
    for (int i = 0; i < 6; ++i)
        centers.emplace_back(0.7 * i, 0.4 * std::sin(i), 0.3 * std::cos(2.0 * i));
    std::vector<rt::Candidate> cands = rt::candidatesAlongX(centers, 1.0, 1.0);
    std::sort(cands.begin(), cands.end(), [](auto& a, auto& b) { return a.t0 < b.t0; });
    tr::raymarch::RayField field;
    rt::assign(field, cands, 1.0);
    for (double t = -2.0; t < 6.0; t += 0.25) {
        const double bound = rt::remainingBound(field, t, 100.0);
        for (double s = t; s < 7.0; s += 0.01)
            ASSERT_LE(tr::raymarch::sampleField(field, s, 0.0).value, bound) << t << " " << s;
    }
}
