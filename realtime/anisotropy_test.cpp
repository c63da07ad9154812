#include "realtime/anisotropy.h"

#include <gtest/gtest.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <random>

#include "core/symmetric_eigen.h"

namespace twinrender::realtime {
namespace {

constexpr float SPACING = 0.1f;

// nx x ny x nz particles of a cubic lattice (spacing SPACING, smoothing length h) about the
// origin, optionally jittered by up to `jitter` spacings on each axis.
core::ParticleSet lattice(int nx, int ny, int nz, float h, float jitter = 0.0f, unsigned seed = 1) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-jitter, jitter);
    core::ParticleSet ps;
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x) {
                const glm::vec3 p(x - (nx - 1) / 2.0f, y - (ny - 1) / 2.0f, z - (nz - 1) / 2.0f);
                ps.position.push_back(SPACING * (p + glm::vec3(u(rng), u(rng), u(rng))));
                ps.h.push_back(h);
            }
    const std::size_t n = ps.position.size();
    ps.volume.assign(n, SPACING * SPACING * SPACING);
    ps.normal.assign(n, glm::vec3(0.0f, 0.0f, 1.0f));
    ps.body.assign(n, 0);
    return ps;
}

// The index of the particle nearest to p.
std::size_t nearest(const core::ParticleSet& ps, const glm::vec3& p) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < ps.size(); ++i)
        if (glm::distance(ps.position[i], p) < glm::distance(ps.position[best], p)) best = i;
    return best;
}

// The axis lengths, descending, and the shortest axis's unit direction.
struct Axes {
    float length[3];
    glm::vec3 shortest;
};
Axes axesOf(const Ellipsoid& e) {
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3,
              [&](int a, int b) { return glm::length(e.axes[a]) > glm::length(e.axes[b]); });
    Axes out{};
    for (int k = 0; k < 3; ++k) out.length[k] = glm::length(e.axes[order[k]]);
    out.shortest = glm::normalize(e.axes[order[2]]);
    return out;
}

// Inside a single layer the neighbourhood has no spread across the layer: the ellipsoid is
// the paper's clamp exactly, k_r : k_r : 1 (the square lattice spreads equally along x and y),
// its short axis along the layer's normal, its volume the impostor sphere's. About the smoothed
// centre ("centre") it is centred on the particle (the neighbourhood is symmetric about it);
// "surface" lifts it along the normal until it reaches as far as the sphere.
TEST(Anisotropy, ALayerFlattensToTheAxisRatioClamp) {
    const core::ParticleSet ps = lattice(15, 15, 1, 2.0f * SPACING);  // ~48 neighbours
    const std::size_t centre = nearest(ps, glm::vec3(0.0f));
    const float r = 0.09f;
    const std::vector<float> radii(ps.size(), r);
    for (double ratio : {4.0, 2.0}) {
        AnisotropySettings s;
        s.maxAxisRatio = ratio;
        s.anchor = EllipsoidAnchor::Centre;
        const Ellipsoid e = anisotropicEllipsoids(ps, radii, s)[centre];
        const Axes a = axesOf(e);
        const float k = static_cast<float>(ratio);
        EXPECT_NEAR(a.length[0], r * std::cbrt(k), 1e-6f) << ratio;
        EXPECT_NEAR(a.length[1], r * std::cbrt(k), 1e-6f);
        EXPECT_NEAR(a.length[2], r / std::cbrt(k * k), 1e-6f);
        EXPECT_NEAR(std::abs(a.shortest.z), 1.0f, 1e-6f);
        EXPECT_NEAR(a.length[0] * a.length[1] * a.length[2], r * r * r, 1e-6f * r * r * r);
        EXPECT_LT(glm::length(e.shift), 1e-7f);
        // The axes are orthogonal.
        EXPECT_NEAR(glm::dot(e.axes[0], e.axes[1]), 0.0f, 1e-8f);
        EXPECT_NEAR(glm::dot(e.axes[0], e.axes[2]), 0.0f, 1e-8f);
        s.anchor = EllipsoidAnchor::Surface;
        const Ellipsoid lifted = anisotropicEllipsoids(ps, radii, s)[centre];
        EXPECT_NEAR(lifted.shift.z, r - a.length[2], 1e-6f);
        EXPECT_LT(glm::length(glm::vec2(lifted.shift)), 1e-7f);
    }
}

// In a slab two layers thick (the suite's h = 1.3 spacings), a particle away from the edges
// is flattened along the normal, no further than k_r allows.
TEST(Anisotropy, ASlabParticleIsFlattenedAlongTheNormal) {
    const core::ParticleSet ps = lattice(12, 12, 2, 1.3f * SPACING);
    const std::size_t i = nearest(ps, glm::vec3(0.05f, 0.05f, 0.05f));
    const std::vector<float> radii(ps.size(), 0.117f);
    AnisotropySettings s;
    s.anchor = EllipsoidAnchor::Centre;
    const Ellipsoid e = anisotropicEllipsoids(ps, radii, s)[i];
    const Axes a = axesOf(e);
    EXPECT_NEAR(std::abs(a.shortest.z), 1.0f, 1e-5f);
    EXPECT_NEAR(a.length[0], a.length[1], 1e-5f);
    EXPECT_GT(a.length[0] / a.length[2], 2.0f);
    EXPECT_LE(a.length[0] / a.length[2], 4.0f * (1.0f + 1e-5f));
    // The neighbourhood reaches further into its own layer than into the other: the centre
    // moves towards the other layer.
    EXPECT_LT(e.shift.z, 0.0f);
}

// The module's ellipsoid of particles of a disordered set equals the paper's formulas summed
// over every particle (no grid): weighted mean, smoothed centre, covariance, clamp.
TEST(Anisotropy, MatchesTheFormulasSummedOverEveryParticle) {
    const core::ParticleSet ps = lattice(9, 9, 5, 1.3f * SPACING, 0.3f, 3);
    const std::vector<float> radii(ps.size(), 0.1f);
    AnisotropySettings s;
    s.smoothing = 0.75;
    s.anchor = EllipsoidAnchor::Centre;
    const std::vector<Ellipsoid> ellipsoids = anisotropicEllipsoids(ps, radii, s);
    int flattened = 0;
    for (std::size_t i :
         {nearest(ps, glm::vec3(0.4f, 0.0f, 0.0f)), nearest(ps, glm::vec3(0.0f, 0.0f, 0.2f)),
          nearest(ps, glm::vec3(0.0f)), nearest(ps, glm::vec3(0.3f, 0.1f, 0.2f))}) {
        const glm::dvec3 x(ps.position[i]);
        const double radius = 2.0 * ps.h[i];
        double weight = 0.0;
        glm::dvec3 sum(0.0);
        int neighbours = 0;
        for (std::size_t j = 0; j < ps.size(); ++j) {
            const double d = glm::distance(glm::dvec3(ps.position[j]), x);
            if (d >= radius) continue;
            const double w = 1.0 - std::pow(d / radius, 3.0);
            weight += w;
            sum += w * glm::dvec3(ps.position[j]);
            neighbours += j != i;
        }
        const glm::dvec3 mean = sum / weight;
        glm::dmat3 covariance(0.0);
        for (std::size_t j = 0; j < ps.size(); ++j) {
            const double d = glm::distance(glm::dvec3(ps.position[j]), x);
            if (d >= radius) continue;
            const glm::dvec3 o = glm::dvec3(ps.position[j]) - mean;
            covariance += (1.0 - std::pow(d / radius, 3.0)) / weight * glm::outerProduct(o, o);
        }
        const Ellipsoid& e = ellipsoids[i];
        ASSERT_GE(neighbours, s.minNeighbours) << i;
        const glm::dvec3 shift = s.smoothing * (mean - x);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(e.shift[c], shift[c], 1e-6) << i;
        const core::SymmetricEigen eigen = core::symmetricEigen(covariance);
        glm::dvec3 spread;
        for (int k = 0; k < 3; ++k) spread[k] = std::max(eigen.values[k], eigen.values[0] / 4.0);
        const double scale = 0.1 / std::cbrt(spread.x * spread.y * spread.z);
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(glm::length(e.axes[k]), scale * spread[k], 1e-5) << i << " " << k;
            // Each axis is along the covariance's eigenvector (up to sign), unless two
            // eigenvalues are (nearly) equal.
            EXPECT_GT(std::abs(glm::dot(glm::dvec3(glm::normalize(e.axes[k])), eigen.vectors[k])),
                      0.999)
                << i << " " << k;
        }
        flattened += spread[0] / spread[2] > 1.5;
    }
    EXPECT_GE(flattened, 2);  // the boundary particles at least
}

// "surface" moves the smoothed centre along the particle's normal only, until the ellipsoid
// reaches as far along it as the impostor sphere: the top of a slab stays where the spheres'
// was, while across it the centre keeps the smoothing.
TEST(Anisotropy, TheSurfaceAnchorKeepsTheSpheresReachAlongTheNormal) {
    core::ParticleSet ps = lattice(10, 10, 4, 1.3f * SPACING, 0.2f, 5);
    const glm::vec3 normal = glm::normalize(glm::vec3(0.1f, -0.2f, 1.0f));
    ps.normal.assign(ps.size(), normal);
    const std::vector<float> radii(ps.size(), 0.11f);
    AnisotropySettings s;
    s.anchor = EllipsoidAnchor::Centre;
    const std::vector<Ellipsoid> centred = anisotropicEllipsoids(ps, radii, s);
    s.anchor = EllipsoidAnchor::Surface;
    const std::vector<Ellipsoid> lifted = anisotropicEllipsoids(ps, radii, s);
    const std::size_t top = nearest(ps, glm::vec3(0.0f, 0.0f, 0.15f));
    int moved = 0;
    for (std::size_t i : {top, nearest(ps, glm::vec3(0.0f)), nearest(ps, glm::vec3(0.4f))}) {
        const Ellipsoid& e = lifted[i];
        const glm::vec3 support(glm::dot(e.axes[0], normal), glm::dot(e.axes[1], normal),
                                glm::dot(e.axes[2], normal));
        EXPECT_NEAR(glm::dot(e.shift, normal) + glm::length(support), radii[i], 1e-6f) << i;
        const glm::vec3 across = e.shift - centred[i].shift;
        EXPECT_NEAR(glm::length(across - glm::dot(across, normal) * normal), 0.0f, 1e-6f) << i;
        for (int k = 0; k < 3; ++k) EXPECT_EQ(e.axes[k], centred[i].axes[k]);
        moved += glm::length(across) > 0.1f * radii[i];
    }
    EXPECT_GE(moved, 1);  // the top layer's, flattened and pulled inwards about its centre
    EXPECT_LT(glm::dot(centred[top].shift, normal), 0.0f);
}

// An isolated particle, and one with fewer than N_eps neighbours, stays the sphere of its
// impostor radius about its own position; so does every particle with k_r = 1.
TEST(Anisotropy, SparseParticlesStaySpheres) {
    core::ParticleSet lone = lattice(1, 1, 1, 0.13f);
    const std::vector<Ellipsoid> one = anisotropicEllipsoids(lone, {{0.02f}}, AnisotropySettings{});
    ASSERT_EQ(one.size(), 1u);
    EXPECT_TRUE(one[0].isSphere());
    EXPECT_EQ(one[0].axes[0].x, 0.02f);

    const core::ParticleSet row = lattice(30, 1, 1, 0.13f);  // 4 neighbours each
    const std::vector<float> radii(row.size(), 0.1f);
    for (const Ellipsoid& e : anisotropicEllipsoids(row, radii, AnisotropySettings{}))
        EXPECT_TRUE(e.isSphere());
    AnisotropySettings few;
    few.minNeighbours = 4;
    const Ellipsoid stretched = anisotropicEllipsoids(row, radii, few)[15];
    EXPECT_FALSE(stretched.isSphere());
    EXPECT_NEAR(axesOf(stretched).length[0] / axesOf(stretched).length[2], 4.0f, 1e-4f);

    const core::ParticleSet slab = lattice(10, 10, 2, 0.13f);
    AnisotropySettings round;
    round.maxAxisRatio = 1.0;
    round.smoothing = 0.0;
    for (const Ellipsoid& e :
         anisotropicEllipsoids(slab, std::vector<float>(slab.size(), 0.1f), round)) {
        const Axes a = axesOf(e);
        EXPECT_NEAR(a.length[0], 0.1f, 1e-6f);
        EXPECT_NEAR(a.length[2], 0.1f, 1e-6f);
    }
}

// Every particle's sum runs in the grid's fixed order: the ellipsoids are bit-identical for
// any thread count.
TEST(Anisotropy, DeterministicWhateverTheThreadCount) {
    const core::ParticleSet ps = lattice(24, 20, 6, 1.3f * SPACING, 0.35f, 11);
    const std::vector<float> radii(ps.size(), 0.11f);
    auto with = [&](int threads) {
        tbb::task_arena arena(threads);
        std::vector<Ellipsoid> out;
        arena.execute([&] { out = anisotropicEllipsoids(ps, radii, AnisotropySettings{}); });
        return out;
    };
    const std::vector<Ellipsoid> one = with(1),
                                 many = with(std::max(2, tbb::info::default_concurrency()));
    ASSERT_EQ(one.size(), many.size());
    EXPECT_EQ(std::memcmp(one.data(), many.data(), one.size() * sizeof(Ellipsoid)), 0);
}

TEST(Anisotropy, TheCacheKeepsTheAnswerOfAnUnchangedSet) {
    core::ParticleSet ps = lattice(8, 8, 3, 1.3f * SPACING);
    std::vector<float> radii(ps.size(), 0.11f);
    AnisotropyCache cache;
    const std::vector<Ellipsoid> first = cache.ellipsoids(ps, radii, AnisotropySettings{});
    EXPECT_FALSE(cache.reused());
    cache.ellipsoids(ps, radii, AnisotropySettings{});
    EXPECT_TRUE(cache.reused());
    AnisotropySettings other;
    other.smoothing = 0.5;
    cache.ellipsoids(ps, radii, other);
    EXPECT_FALSE(cache.reused());
    other.anchor = EllipsoidAnchor::Centre;
    cache.ellipsoids(ps, radii, other);
    EXPECT_FALSE(cache.reused());
    radii[3] = 0.05f;
    cache.ellipsoids(ps, radii, other);
    EXPECT_FALSE(cache.reused());
    ps.position[5].x += 0.01f;
    const std::vector<Ellipsoid>& moved = cache.ellipsoids(ps, radii, other);
    EXPECT_FALSE(cache.reused());
    EXPECT_NE(std::memcmp(moved.data(), first.data(), first.size() * sizeof(Ellipsoid)), 0);
}

}  // namespace
}  // namespace twinrender::realtime
