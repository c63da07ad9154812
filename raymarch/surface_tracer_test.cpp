// The secondary rays of one hit, traced together (one gather of the spheres their cone meets,
// each ray selecting from it), give each ray's answer exactly as it is traced alone.
#include "raymarch/surface_tracer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "raymarch/ao_hemisphere.h"
#include "raymarch/testing/renderer_scenes.h"

namespace tr = twinrender;

namespace {

// A point above the lattice floor of SphereOverFloor, outside every support, as a hit.
tr::raymarch::SurfaceHit pointAboveTheFloor() {
    tr::raymarch::SurfaceHit from;
    from.position = from.outside = {0.35, -0.2, 0.3};
    from.normal = {0.0f, 0.0f, 1.0f};
    from.hRef = 0.13;
    return from;
}

// SphereOverFloor's tracer, its workspace, and the hit the rays leave from.
struct TracerAboveTheFloor {
    const tr::raymarch::testing::SphereOverFloor f;
    tr::raymarch::EmbreeDevice device;
    const tr::core::Camera camera{f.s.scene.camera};
    const tr::raymarch::SurfaceTracer tracer{device, camera, f.s.particles, f.settings, true};
    const tr::raymarch::SurfaceTracer::WorkspacePtr w = tracer.makeWorkspace();
    const tr::raymarch::SurfaceHit from = pointAboveTheFloor();
};

}  // namespace

TEST(SurfaceTracer, RaysOfOneHitTracedTogetherMeetWhatEachMeetsAlone) {
    const TracerAboveTheFloor t;
    const auto& f = t.f;
    const auto& tracer = t.tracer;
    const auto& w = t.w;
    const auto& from = t.from;
    // Toward the sphere (a cone about it, some of whose rays miss it and go on to the scene's
    // bounds) and over the hemisphere below (the floor).
    std::vector<glm::dvec3> directions;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    glm::dvec3 u, v;
    const glm::dvec3 axis = glm::normalize(f.centre - from.outside);
    tr::raymarch::orthonormalBasis(axis, u, v);
    for (int k = 0; k < 48; ++k)
        directions.push_back(
            tr::raymarch::coneDirection(axis, u, v, 0.2, glm::dvec2(unit(rng), unit(rng))));
    const glm::dvec3 down(0.0, 0.0, -1.0);
    tr::raymarch::orthonormalBasis(down, u, v);
    for (int k = 0; k < 16; ++k)
        directions.push_back(
            tr::raymarch::hemisphereDirection(down, u, v, glm::dvec2(unit(rng), unit(rng))));
    const double reach = glm::length(f.centre - from.outside) + f.radius;
    for (const std::vector<glm::dvec3>& set :
         {std::vector<glm::dvec3>(directions.begin(), directions.begin() + 48), directions}) {
        const int n = static_cast<int>(set.size());
        std::vector<tr::raymarch::SurfaceHit> hits(set.size());
        auto found = std::make_unique<bool[]>(set.size());
        // The cone toward the sphere: the downward directions lie outside it, and then the
        // cone of the directions themselves is taken.
        tracer.traceFirst(from, set.data(), n, axis, std::cos(std::acos(1.0 - 0.2)), reach,
                          hits.data(), found.get(), *w);
        int onSphere = 0, onFloor = 0, none = 0;
        for (int j = 0; j < n; ++j) {
            tr::raymarch::SurfaceHit alone;
            ASSERT_EQ(tracer.traceFirst(from, set[j], alone, *w), found[j]) << j;
            if (!found[j]) {
                ++none;
                continue;
            }
            // Bit for bit: the same particles summed in the same order.
            EXPECT_EQ(hits[j].t, alone.t) << j;
            EXPECT_EQ(hits[j].normal, alone.normal) << j;
            EXPECT_EQ(hits[j].body, alone.body) << j;
            (hits[j].body == 1 ? onSphere : onFloor) += 1;
        }
        // Every kind of answer was met.
        EXPECT_GT(onSphere, 10);
        EXPECT_GT(none, 0);
        if (n > 48) {
            EXPECT_GE(onFloor, 12);  // the shallowest may pass the floor's edge
        }
    }
}

TEST(SurfaceTracer, OcclusionRaysOfOneHitTracedTogetherAreOpenWhereEachIsAlone) {
    const TracerAboveTheFloor t;
    const auto& tracer = t.tracer;
    const auto& w = t.w;
    const auto& from = t.from;
    // The whole sphere of directions: the floor below, the ball above, open sky between.
    // Within radius 3 their neighbourhood holds the whole floor, more spheres than one hit
    // gathers: these rays gather per segment as camera rays do, and each ray alone (its own
    // narrow cone) selects from a gather of its own.
    const std::vector<glm::dvec3> directions =
        tr::raymarch::aoDirections(glm::dvec3(0.0, 0.0, 1.0), 6, 17);
    std::vector<glm::dvec3> all = directions;
    for (const glm::dvec3& d : directions) all.push_back(glm::dvec3(d.x, d.y, -d.z));
    const int n = static_cast<int>(all.size());
    for (const double radius : {0.6, 3.0}) {
        auto open = std::make_unique<bool[]>(all.size());
        tracer.resetCounters(*w);
        tracer.traceOpen(from, all.data(), n, radius, *w, open.get());
        const std::uint64_t gathers = tracer.counters(*w).bundles;
        int closed = 0;
        for (int j = 0; j < n; ++j) {
            bool alone = false;
            tracer.traceOpen(from, &all[j], 1, radius, *w, &alone);
            EXPECT_EQ(open[j], alone) << j << " within " << radius;
            closed += open[j] ? 0 : 1;
        }
        EXPECT_GE(closed, n / 4) << radius;  // the floor, below most downward directions
        if (radius > 1.0) {
            EXPECT_GT(gathers, 0u);  // the neighbourhood was too large: gathers per segment
        } else {
            EXPECT_EQ(gathers, 0u);
        }
    }
}
