// The bundle gather against brute force: every support sphere that a ray of the bundle
// crosses over its interval is reported, and nothing far from every ray is; the first-entry
// queries never report an entry after the true first one.
#include "raymarch/bundle_gather.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <random>

namespace tr = twinrender;
using tr::raymarch::BundleGather;
using tr::raymarch::RayBundle;

namespace {

struct Spheres {
    std::vector<glm::vec3> centers;
    std::vector<float> radius, margin;
};

// A cloud of particles of mixed sizes, denser than any lattice (so groups overlap).
Spheres randomSpheres(std::mt19937& rng, int n, float margin) {
    std::uniform_real_distribution<float> pos(-10.0f, 10.0f), size(0.3f, 1.5f);
    Spheres s;
    for (int i = 0; i < n; ++i) {
        s.centers.push_back({pos(rng), pos(rng), pos(rng)});
        s.radius.push_back(size(rng));
        s.margin.push_back(margin);
    }
    return s;
}

// Distance-based overlap of a sphere with the ray segment o + t d, t in [t0, t1] (double).
double segmentDistance(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1,
                       const glm::dvec3& c) {
    const double t = std::clamp(glm::dot(c - o, d), t0, t1);
    return glm::length(o + t * d - c);
}

struct TestRay {
    glm::dvec3 origin, direction;
    double t0, t1;
};

// Gathers the bundle and checks the result against every sphere.
void checkGather(const BundleGather& gather, const Spheres& s, const std::vector<TestRay>& rays,
                 const glm::dvec3& centralOrigin, const glm::dvec3& centralDirection) {
    RayBundle bundle;
    double tnear = INFINITY, tfar = -INFINITY;
    for (const TestRay& r : rays) {
        bundle.add(r.origin, r.direction, r.t0, r.t1);
        for (double t : {r.t0, r.t1}) {
            const double along =
                glm::dot(r.origin + t * r.direction - centralOrigin, centralDirection);
            tnear = std::min(tnear, along);
            tfar = std::max(tfar, along);
        }
    }
    bundle.finish();
    std::vector<std::uint32_t> out;
    gather.gather(bundle, centralOrigin, centralDirection, std::max(tnear, 0.0), tfar, out);
    std::vector<std::uint32_t> sorted = out;
    std::sort(sorted.begin(), sorted.end());
    ASSERT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end())
        << "a sphere reported twice";
    for (std::size_t i = 0; i < s.centers.size(); ++i) {
        double nearest = INFINITY;
        for (const TestRay& r : rays)
            nearest = std::min(nearest, segmentDistance(r.origin, r.direction, r.t0, r.t1,
                                                        glm::dvec3(s.centers[i])));
        const bool reported = std::binary_search(sorted.begin(), sorted.end(), std::uint32_t(i));
        // Float slack: a sphere within 1e-3 of its radius of a ray may go either way.
        if (nearest < s.radius[i] * (1.0 - 1e-3)) {
            EXPECT_TRUE(reported) << "sphere " << i << " missed";
        } else if (nearest > s.radius[i] * (1.0 + 1e-3)) {
            EXPECT_FALSE(reported) << "sphere " << i << " far from every ray";
        }
    }
}

}  // namespace

TEST(BundleGather, ParallelBundleFindsExactlyTheSpheresItsRaysCross) {
    std::mt19937 rng(7);
    const float margin = 0.4f;
    const Spheres s = randomSpheres(rng, 3000, margin);
    tr::raymarch::EmbreeDevice device;
    BundleGather gather(device, s.centers, s.radius, s.margin);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), len(0.5, 6.0);
    for (int trial = 0; trial < 40; ++trial) {
        const glm::dvec3 dir = glm::normalize(glm::dvec3(unit(rng), unit(rng), unit(rng)));
        const glm::dvec3 mean = glm::dvec3(unit(rng), unit(rng), unit(rng)) * 8.0 - 12.0 * dir;
        // Two axes across the direction: the rays stay within the margin of the central line.
        const glm::dvec3 a = glm::normalize(
            glm::cross(dir, std::abs(dir.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
        const glm::dvec3 b = glm::cross(dir, a);
        std::vector<TestRay> rays;
        for (int k = 0; k < 37; ++k) {
            const double u = unit(rng) * margin * 0.7, v = unit(rng) * margin * 0.7;
            const double t0 = 6.0 + 4.0 * unit(rng);
            rays.push_back({mean + u * a + v * b, dir, t0, t0 + len(rng)});
        }
        checkGather(gather, s, rays, mean, dir);
    }
}

TEST(BundleGather, DivergingBundleFindsExactlyTheSpheresItsRaysCross) {
    std::mt19937 rng(11);
    // Rays from one point within `spread` radians of the central ray: near a sphere at
    // distance D they pass within (D + r) spread of it; the margin covers D up to 40.
    const double spread = 0.004;
    Spheres s = randomSpheres(rng, 3000, 0.0f);
    for (std::size_t i = 0; i < s.centers.size(); ++i)
        s.margin[i] = static_cast<float>((40.0 + s.radius[i]) * spread);
    tr::raymarch::EmbreeDevice device;
    BundleGather gather(device, s.centers, s.radius, s.margin);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), len(0.5, 4.0);
    const glm::dvec3 eye(0.0, 0.0, 25.0);
    for (int trial = 0; trial < 40; ++trial) {
        const glm::dvec3 target(unit(rng) * 6.0, unit(rng) * 6.0, unit(rng) * 6.0);
        const glm::dvec3 dir = glm::normalize(target - eye);
        const glm::dvec3 a = glm::normalize(glm::cross(dir, glm::dvec3(0, 1, 0)));
        const glm::dvec3 b = glm::cross(dir, a);
        std::vector<TestRay> rays;
        for (int k = 0; k < 64; ++k) {
            const glm::dvec3 d =
                glm::normalize(dir + (unit(rng) * a + unit(rng) * b) * (spread * 0.7));
            const double t0 = 15.0 + 8.0 * unit(rng);
            rays.push_back({eye, d, t0, t0 + len(rng)});
        }
        checkGather(gather, s, rays, eye, dir);
    }
}

TEST(BundleGather, FirstEntryIsNeverAfterTheTrueOne) {
    std::mt19937 rng(3);
    const Spheres s = randomSpheres(rng, 2000, 0.25f);
    tr::raymarch::EmbreeDevice device;
    BundleGather gather(device, s.centers, s.radius, s.margin);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    BundleGather::Query queries[BundleGather::PACKET];
    for (int trial = 0; trial < 200; ++trial) {
        const glm::dvec3 o = glm::dvec3(unit(rng), unit(rng), unit(rng)) * 15.0;
        const glm::dvec3 d = glm::normalize(glm::dvec3(unit(rng), unit(rng), unit(rng)));
        const double tnear = 0.5 + std::abs(unit(rng)), tfar = 30.0;
        // Brute force: the first entry into a grown sphere (radii times `scale`) within
        // [tnear, tfar].
        auto firstEntry = [&](double scale) {
            double first = INFINITY;
            for (std::size_t i = 0; i < s.centers.size(); ++i) {
                const double r = (s.radius[i] + s.margin[i]) * scale;
                const glm::dvec3 w = glm::dvec3(s.centers[i]) - o;
                const double tc = glm::dot(w, d), chord2 = r * r - glm::dot(w - tc * d, w - tc * d);
                if (chord2 <= 0.0 || tc + std::sqrt(chord2) < tnear) continue;
                const double entry = std::max(tc - std::sqrt(chord2), tnear);
                if (entry <= tfar) first = std::min(first, entry);
            }
            return first;
        };
        const double truth = firstEntry(1.0);
        // The query's float slack (radii 1e-4 larger, entries 1e-4 r earlier) moves a grazing
        // entry a long way: it may come no earlier than that of radii 1e-3 larger, less 1e-3 r.
        const double earliest = firstEntry(1.001) - 1e-3 * 2.0;
        BundleGather::Entry e{};
        const bool found = gather.firstEntry(o, d, tnear, tfar, e);
        queries[trial % BundleGather::PACKET] = {o, d, tnear, tfar};
        if (!std::isfinite(truth)) {
            EXPECT_FALSE(found);
            continue;
        }
        ASSERT_TRUE(found);
        EXPECT_LE(e.t, truth + 1e-4) << "trial " << trial;
        EXPECT_GE(e.t, earliest) << "trial " << trial;
        // The packet query agrees with the single one for the same line.
        BundleGather::Entry packet[BundleGather::PACKET];
        const std::uint32_t mask =
            gather.firstEntries(1, &queries[trial % BundleGather::PACKET], packet);
        ASSERT_EQ(mask, 1u);
        EXPECT_NEAR(packet[0].t, e.t, 1e-4);
    }
}

// A set of the spheres selects, for one ray, exactly what a gather of that ray alone reports
// (the same test, so that fields built from either sum the same particles in the same
// order), also for rays that graze a sphere within the tests' float slack; a subset
// selected over a ray's whole interval selects as the full set over any part of it; and the
// set's first entry into a grown sphere is the first-entry query's.
TEST(SphereSet, SelectsExactlyWhatAGatherOfTheRayReports) {
    std::mt19937 rng(5);
    const Spheres s = randomSpheres(rng, 2000, 0.3f);
    tr::raymarch::EmbreeDevice device;
    BundleGather gather(device, s.centers, s.radius, s.margin);
    tr::raymarch::SphereSet all, subset;
    for (std::size_t i = 0; i < s.centers.size(); ++i)
        all.add(s.centers[i], s.radius[i],
                (s.radius[i] + s.margin[i]) * (1.0f + tr::raymarch::GATHER_SLACK),
                static_cast<std::uint32_t>(i));
    all.finish();
    std::uniform_real_distribution<double> unit(-1.0, 1.0), graze(-2e-4, 2e-4);
    int grazing = 0, entries = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const glm::dvec3 o = glm::dvec3(unit(rng), unit(rng), unit(rng)) * 10.0;
        glm::dvec3 d = glm::normalize(glm::dvec3(unit(rng), unit(rng), unit(rng)));
        if (trial % 2 == 1) {
            // Aimed to pass a sphere at its radius times 1 + graze (its side or its cap).
            const std::size_t i = static_cast<std::size_t>(trial) % s.centers.size();
            const glm::dvec3 c(s.centers[i]);
            const glm::dvec3 across =
                glm::normalize(glm::cross(c - o, glm::dvec3(unit(rng), unit(rng), unit(rng))));
            d = glm::normalize(c + across * (double(s.radius[i]) * (1.0 + graze(rng))) - o);
            ++grazing;
        }
        const double t0 = 0.5 * std::abs(unit(rng)), t1 = t0 + 4.0 + 4.0 * std::abs(unit(rng));
        RayBundle bundle;
        bundle.add(o, d, t0, t1);
        bundle.finish();
        std::vector<std::uint32_t> gathered, selected;
        gather.gather(bundle, o, d, t0 - 1e-5, t1 + 1e-5, gathered);
        std::sort(gathered.begin(), gathered.end());
        all.select(o, d, t0, t1, &selected, nullptr);
        EXPECT_EQ(selected, gathered) << "trial " << trial;
        // A part of the ray, from the whole ray's subset.
        all.select(o, d, t0, t1, nullptr, &subset);
        EXPECT_EQ(subset.size(), selected.size());
        const double a = t0 + 0.3 * (t1 - t0), b = t0 + 0.6 * (t1 - t0);
        std::vector<std::uint32_t> part, partOfSubset;
        all.select(o, d, a, b, &part, nullptr);
        subset.select(o, d, a, b, &partOfSubset, nullptr);
        EXPECT_EQ(partOfSubset, part) << "trial " << trial;
        // The first entry into a grown sphere, where the set decides it, is the query's.
        double t = 0.0;
        std::uint32_t prim = 0;
        BundleGather::Entry e{};
        const bool found = gather.firstEntry(o, d, t0, t1, e);
        if (all.firstEntry(o, d, t0, t1, INFINITY, t, prim)) {
            ++entries;
            ASSERT_TRUE(found) << "trial " << trial;
            EXPECT_EQ(t, e.t) << "trial " << trial;
            EXPECT_EQ(s.radius[prim], s.radius[e.prim]) << "trial " << trial;
        }
    }
    EXPECT_EQ(grazing, 150);
    EXPECT_GT(entries, 100);
}
