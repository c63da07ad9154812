#include "realtime/anisotropy.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "core/particle_grid.h"
#include "core/symmetric_eigen.h"

namespace twinrender::realtime {

namespace {

// The neighbourhood radius r_i = 2 h_i (Yu & Turk: the support of the SPH kernel).
constexpr double NEIGHBOURHOOD_SCALE = 2.0;

// The weighted moments of particle i's neighbourhood, positions relative to x_i (in double:
// neighbours lie within 2 h of x_i, and the covariance takes differences of their squares).
struct Neighbourhood {
    double weight = 0.0;     // sum_j w_ij
    glm::dvec3 first{0.0};   // sum_j w_ij d_j, d_j = x_j - x_i
    glm::dmat3 second{0.0};  // sum_j w_ij d_j d_j^T
    int neighbours = 0;      // j != i within r_i
};

Neighbourhood gather(const core::ParticleGrid& grid, const glm::dvec3& x, std::uint32_t self,
                     double radius) {
    Neighbourhood n;
    const double inverse = 1.0 / radius;
    grid.visitBall(x, radius,
                   [&](const core::ParticleGrid::Level& g, std::uint32_t begin, std::uint32_t end) {
                       for (std::uint32_t k = begin; k < end; ++k) {
                           const glm::dvec3 d = glm::dvec3(g.px[k], g.py[k], g.pz[k]) - x;
                           const double q = glm::length(d) * inverse;
                           if (q >= 1.0) continue;
                           const double w = 1.0 - q * q * q;
                           n.weight += w;
                           n.first += w * d;
                           n.second += w * glm::outerProduct(d, d);
                           n.neighbours += g.index[k] != self;
                       }
                   });
    return n;
}

// anchor = "surface": the shift that moves the ellipsoid along the unit normal until it
// reaches `radius` along it, as the impostor sphere about the particle does. Its reach along
// n from the particle is shift . n + |A^T n| (|A^T n|: the support of {A u : |u| <= 1}).
glm::dvec3 surfaceShift(const glm::dvec3& shift, const glm::dmat3& axes, const glm::dvec3& normal,
                        double radius) {
    const double reach = glm::dot(shift, normal) + glm::length(normal * axes);
    return shift + (radius - reach) * normal;
}

Ellipsoid ellipsoidOf(const Neighbourhood& n, float radius, const glm::vec3& normal,
                      const AnisotropySettings& settings) {
    const Ellipsoid sphere = Ellipsoid::sphere(radius);
    if (n.neighbours < settings.minNeighbours || !(n.weight > 0.0)) return sphere;
    const glm::dvec3 mean = n.first / n.weight;
    const glm::dmat3 covariance = n.second / n.weight - glm::outerProduct(mean, mean);
    const core::SymmetricEigen e = core::symmetricEigen(covariance);
    const double largest = e.values[0];
    if (!(largest > 0.0)) return sphere;
    glm::dvec3 spread;
    for (int k = 0; k < 3; ++k) spread[k] = std::max(e.values[k], largest / settings.maxAxisRatio);
    // Unit product: the volume of the sphere of the impostor radius.
    const double scale = double(radius) / std::cbrt(spread.x * spread.y * spread.z);
    glm::dmat3 axes;
    for (int k = 0; k < 3; ++k) axes[k] = scale * spread[k] * e.vectors[k];
    glm::dvec3 shift = settings.smoothing * mean;
    const double normalLength = glm::length(glm::dvec3(normal));
    if (settings.anchor == EllipsoidAnchor::Surface && normalLength > 0.0)
        shift = surfaceShift(shift, axes, glm::dvec3(normal) / normalLength, radius);
    Ellipsoid out;
    out.shift = glm::vec3(shift);
    for (int k = 0; k < 3; ++k) out.axes[k] = glm::vec3(axes[k]);
    return out;
}

Ellipsoid particleEllipsoid(const core::ParticleGrid& grid, const core::ParticleSet& ps,
                            std::size_t i, float radius, const AnisotropySettings& settings) {
    if (!(radius > 0.0f)) return Ellipsoid::sphere(radius);  // no surface: not drawn
    const Neighbourhood n = gather(grid, glm::dvec3(ps.position[i]), static_cast<std::uint32_t>(i),
                                   NEIGHBOURHOOD_SCALE * double(ps.h[i]));
    return ellipsoidOf(n, radius, ps.normal[i], settings);
}

}  // namespace

bool Ellipsoid::isSphere() const {
    const float r = axes[0].x;
    return shift == glm::vec3(0.0f) && axes[0] == glm::vec3(r, 0.0f, 0.0f) &&
           axes[1] == glm::vec3(0.0f, r, 0.0f) && axes[2] == glm::vec3(0.0f, 0.0f, r);
}

Ellipsoid Ellipsoid::sphere(float r) {
    Ellipsoid s;
    s.axes[0] = {r, 0.0f, 0.0f};
    s.axes[1] = {0.0f, r, 0.0f};
    s.axes[2] = {0.0f, 0.0f, r};
    return s;
}

std::vector<Ellipsoid> anisotropicEllipsoids(const core::ParticleSet& ps,
                                             std::span<const float> radii,
                                             const AnisotropySettings& settings) {
    std::vector<Ellipsoid> out(ps.size());
    if (ps.size() == 0) return out;
    const core::ParticleGrid grid(ps);
    // Each particle is computed alone, its neighbours summed in the grid's fixed order: the
    // same result for any thread count.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ps.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i)
                              out[i] = particleEllipsoid(grid, ps, i, radii[i], settings);
                      });
    return out;
}

const std::vector<Ellipsoid>& AnisotropyCache::ellipsoids(const core::ParticleSet& ps,
                                                          std::span<const float> radii,
                                                          const AnisotropySettings& settings) {
    return mCache.get(
        ps, [&] { return anisotropicEllipsoids(ps, radii, settings); }, radii, settings);
}

}  // namespace twinrender::realtime
