// The root search on fields whose crossings are known analytically.
#include "raymarch/first_crossing.h"

#include <gtest/gtest.h>

#include "core/sph_kernel.h"
#include "raymarch/testing/ray_field_testing.h"

namespace tr = twinrender;
namespace rt = twinrender::raymarch::testing;

TEST(FirstCrossing, SingleCandidateCrossingIsTheAnalyticRadius) {
    const double h = 0.7, v = tr::core::maxParticleVolume(h);
    const double level = 0.5 * v * tr::core::m4Kernel(0.0, h);  // a sphere of about 0.58 h
    const double radius = rt::singleParticleRadius(v, h, level);
    const double origin[3] = {0.0, 0.0, -5.0}, dir[3] = {0.0, 0.0, 1.0},
                 center[3] = {0.0, 0.0, 0.0};
    rt::Candidate c;
    ASSERT_TRUE(rt::makeCandidate(origin, dir, center, h, v, 0, c));
    tr::raymarch::CrossingSettings cs;
    cs.level = level;
    cs.tolerance = 1e-4 * h;
    cs.maxStep = 0.5 * h;
    tr::raymarch::RayField field;
    rt::assign(field, {c}, 0.0);
    const auto crossing = tr::raymarch::findFirstCrossing(field, 0.0, 10.0, cs);
    ASSERT_EQ(crossing.status, tr::raymarch::Crossing::Status::Hit);
    EXPECT_NEAR(crossing.t, 5.0 - radius, 1e-4 * h);
    EXPECT_LT(crossing.tBelow, 5.0 - radius);
}

namespace {

// A particle grazed by a ray along z at t = 5: its field peaks just above the level over a
// short stretch (a few 1e-3 h), a crossing that a careless step would pass over.
struct ThinBump {
    tr::raymarch::CrossingSettings settings;
    tr::raymarch::RayField field;
    ThinBump() {
        const double h = 1.0, v = tr::core::maxParticleVolume(h);
        const double d = 0.3;  // distance of the ray from the particle
        settings.level = v * tr::core::m4Kernel(d, h) * 0.9999;
        settings.tolerance = 1e-6;
        settings.maxStep = 0.5;
        const double origin[3] = {0.0, d, -5.0}, dir[3] = {0.0, 0.0, 1.0},
                     center[3] = {0.0, 0.0, 0.0};
        rt::Candidate c;
        EXPECT_TRUE(rt::makeCandidate(origin, dir, center, h, v, 0, c));
        rt::assign(field, {c}, 0.0);
    }
};

}  // namespace

TEST(FirstCrossing, NeverStepsOverAThinBump) {
    const ThinBump bump;
    const auto crossing = tr::raymarch::findFirstCrossing(bump.field, 0.0, 10.0, bump.settings);
    ASSERT_EQ(crossing.status, tr::raymarch::Crossing::Status::Hit);
    EXPECT_LT(crossing.t, 5.0);
    EXPECT_GT(crossing.t, 4.9);
}

TEST(FirstCrossing, AHintBeyondAThinBumpDoesNotSkipIt) {
    // A hint (a neighbour's crossing) well past the bump, as where a ray passes the edge of a
    // near body and its neighbour meets a far one: the bound up to the hint must see the
    // bump, and the crossing found must be the bump's.
    const ThinBump bump;
    for (const double hint : {5.001, 5.05, 6.0, 7.5}) {
        const auto crossing =
            tr::raymarch::findFirstCrossing(bump.field, 0.0, 10.0, bump.settings, hint);
        ASSERT_EQ(crossing.status, tr::raymarch::Crossing::Status::Hit) << hint;
        EXPECT_LT(crossing.t, 5.0) << hint;
        EXPECT_GT(crossing.t, 4.9) << hint;
    }
}
