#include "raymarch/interval_bounds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/sph_kernel.h"
#include "raymarch/testing/ray_field_testing.h"

namespace tr = twinrender;
namespace rt = twinrender::raymarch::testing;

TEST(IntervalBounds, PiecewiseBoundsBoundEachPieceAndAreTighterThanOne) {
    std::vector<glm::dvec3> centers;
    for (int i = 0; i < 8; ++i)
        centers.emplace_back(0.6 * i, 0.5 * std::sin(1.3 * i), 0.4 * std::cos(2.0 * i));
    const std::vector<rt::Candidate> cands = rt::candidatesAlongX(centers, 1.0, 1.0);
    tr::raymarch::RayField field;
    rt::assign(field, cands, 0.5);
    int tighter = 0;
    for (double t = -2.0; t < 5.0; t += 0.37) {
        const double points[] = {t, t + 0.9, t + 1.3, t + 1.4};
        double bounds[tr::raymarch::BOUND_PIECES];
        tr::raymarch::piecewiseBound(field, points, bounds);
        const double whole = tr::raymarch::intervalBound(field, points[0], points[3]);
        for (int k = 0; k < tr::raymarch::BOUND_PIECES; ++k) {
            // Each piece's bound holds over the piece (sampled finely) and never exceeds the
            // bound over the whole interval.
            for (double s = points[k]; s <= points[k + 1]; s += 0.002)
                ASSERT_LE(tr::raymarch::sampleField(field, s, 0.0).value, bounds[k])
                    << t << " piece " << k << " at " << s;
            EXPECT_LE(bounds[k], whole * (1.0 + 1e-6));
        }
        tighter += *std::max_element(bounds, bounds + tr::raymarch::BOUND_PIECES) < 0.9 * whole;
    }
    // Where particles peak in different pieces, the pieces' bounds are well below the whole's.
    EXPECT_GT(tighter, 5);
}
