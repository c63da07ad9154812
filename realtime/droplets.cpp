#include "realtime/droplets.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <numeric>
#include <optional>

#include "core/colour_field.h"
#include "core/particle_grid.h"
#include "core/sph_kernel.h"
#include "core/symmetric_eigen.h"
#include "realtime/impostor_radius.h"

namespace twinrender::realtime {

namespace {

constexpr std::uint32_t NONE = ~std::uint32_t(0);

// Union-find over particle indices, the smaller index as each root (so the root is the
// cluster's first particle whatever order the edges come in).
class Clusters {
  public:
    explicit Clusters(std::size_t n) : mParent(n) { std::iota(mParent.begin(), mParent.end(), 0u); }
    std::uint32_t root(std::uint32_t i) {
        while (mParent[i] != i) i = mParent[i] = mParent[mParent[i]];
        return i;
    }
    void join(std::uint32_t a, std::uint32_t b) {
        a = root(a), b = root(b);
        if (a != b) mParent[std::max(a, b)] = std::min(a, b);
    }

  private:
    std::vector<std::uint32_t> mParent;
};

// The particles within `radius` of x, other than `self`, at most `limit` of them (the count
// stops there).
template <typename Visit>
int forNeighbours(const core::ParticleGrid& grid, const glm::dvec3& x, std::uint32_t self,
                  double radius, int limit, Visit&& visit) {
    int count = 0;
    grid.visitBall(x, radius,
                   [&](const core::ParticleGrid::Level& g, std::uint32_t begin, std::uint32_t end) {
                       for (std::uint32_t k = begin; k < end && count < limit; ++k) {
                           if (g.index[k] == self) continue;
                           const glm::dvec3 d = glm::dvec3(g.px[k], g.py[k], g.pz[k]) - x;
                           if (glm::dot(d, d) >= radius * radius) continue;
                           ++count;
                           visit(g.index[k]);
                       }
                   });
    return count;
}

// The ellipsoid fitted to the level set around the cluster `members` (module comment), about
// the position of members[0]; nullopt where it cannot be fitted.
std::optional<Ellipsoid> fitEllipsoid(const core::ParticleSet& ps, const core::ColourField& field,
                                      std::span<const std::uint32_t> members, double level) {
    glm::dvec3 mean(0.0);
    for (std::uint32_t i : members) mean += glm::dvec3(ps.position[i]);
    mean /= static_cast<double>(members.size());
    glm::dmat3 covariance(0.0);
    double reach = 0.0;  // beyond reach from the mean, no member's kernel adds to the field
    for (std::uint32_t i : members) {
        const glm::dvec3 d = glm::dvec3(ps.position[i]) - mean;
        covariance += glm::outerProduct(d, d);
        reach = std::max(reach, glm::length(d) + core::M4_SUPPORT * double(ps.h[i]));
    }
    const core::SymmetricEigen eigen = core::symmetricEigen(covariance);
    glm::dvec3 centre = mean;
    glm::dmat3 axes(0.0);
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3 e = eigen.vectors[k];
        const double plus = fieldCrossing(field, mean, e, reach, level);
        const double minus = fieldCrossing(field, mean, -e, reach, level);
        // No surface about the mean, or none found within the cluster's reach.
        if (!(plus > 0.0 && minus > 0.0) || plus >= reach || minus >= reach) return std::nullopt;
        centre += 0.5 * (plus - minus) * e;
        axes[k] = 0.5 * (plus + minus) * e;
    }
    Ellipsoid out;
    out.shift = glm::vec3(centre - glm::dvec3(ps.position[members[0]]));
    for (int k = 0; k < 3; ++k) out.axes[k] = glm::vec3(axes[k]);
    return out;
}

}  // namespace

FieldNormal dropletNormalModel(const Ellipsoid& droplet) {
    glm::mat3 m(0.0f);
    for (const glm::vec3& a : droplet.axes) {
        const float length2 = glm::dot(a, a);
        m += glm::outerProduct(a, a) / (length2 * length2);
    }
    FieldNormal out;
    out.outward = -(m * droplet.shift);
    out.diagonal = glm::vec3(m[0][0], m[1][1], m[2][2]);
    out.offDiagonal = glm::vec3(m[1][0], m[2][0], m[2][1]);
    return out;
}

Droplets fitDroplets(const core::ParticleSet& ps, std::span<const float> radii, double level,
                     int maxAtoms) {
    Droplets out;
    if (maxAtoms < 2 || ps.size() == 0) return out;
    const std::size_t n = ps.size();
    const core::ParticleGrid grid(ps);
    // Sparse particles: fewer than maxAtoms neighbours within 2 h (a cluster's members have
    // at most maxAtoms - 1 neighbours each when nothing else is near).
    std::vector<std::uint8_t> sparse(n, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                              if (!(radii[i] > 0.0f)) continue;
                              const int count = forNeighbours(grid, glm::dvec3(ps.position[i]),
                                                              static_cast<std::uint32_t>(i),
                                                              core::M4_SUPPORT * double(ps.h[i]),
                                                              maxAtoms, [](std::uint32_t) {});
                              sparse[i] = count < maxAtoms;
                          }
                      });
    std::vector<std::uint32_t> candidates;
    for (std::size_t i = 0; i < n; ++i)
        if (sparse[i]) candidates.push_back(static_cast<std::uint32_t>(i));
    if (candidates.empty()) return out;

    const core::ColourField field(ps);
    // Edges: the neighbours of each sparse particle whose midpoint with it is inside the
    // level set. An edge to a particle that is not sparse marks the cluster as part of a body.
    Clusters clusters(n);
    std::vector<std::uint8_t> joinsBody(n, 0);
    for (std::uint32_t i : candidates) {
        const glm::dvec3 x(ps.position[i]);
        forNeighbours(grid, x, i, core::M4_SUPPORT * double(ps.h[i]), maxAtoms,
                      [&](std::uint32_t j) {
                          if (field.value(0.5 * (x + glm::dvec3(ps.position[j]))) <= level) return;
                          if (!sparse[j]) joinsBody[i] = 1;
                          clusters.join(i, j);
                      });
    }
    // The clusters of 2 .. maxAtoms sparse particles, by first particle: (first, member) pairs
    // of the sparse particles only, sorted. A cluster with an edge to a particle that is not
    // sparse has a sparse member marked joinsBody.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> byCluster;
    byCluster.reserve(candidates.size());
    for (std::uint32_t i : candidates) byCluster.emplace_back(clusters.root(i), i);
    std::sort(byCluster.begin(), byCluster.end());
    std::vector<std::uint32_t> firsts;
    std::vector<std::vector<std::uint32_t>> members;
    for (std::size_t k = 0; k < byCluster.size();) {
        std::size_t end = k;
        bool joins = false;
        for (; end < byCluster.size() && byCluster[end].first == byCluster[k].first; ++end)
            joins = joins || joinsBody[byCluster[end].second];
        const std::size_t size = end - k;
        if (!joins && size >= 2 && size <= static_cast<std::size_t>(maxAtoms)) {
            firsts.push_back(byCluster[k].first);
            members.emplace_back();
            for (std::size_t m = k; m < end; ++m) members.back().push_back(byCluster[m].second);
        }
        k = end;
    }
    std::vector<std::optional<Ellipsoid>> fitted(firsts.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, firsts.size(), 16),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t k = range.begin(); k != range.end(); ++k)
                              fitted[k] = fitEllipsoid(ps, field, members[k], level);
                      });
    out.ellipsoids.resize(n);
    for (std::size_t i = 0; i < n; ++i) out.ellipsoids[i] = Ellipsoid::sphere(radii[i]);
    out.radii.assign(radii.begin(), radii.end());
    for (std::size_t k = 0; k < firsts.size(); ++k) {
        if (!fitted[k]) continue;
        const std::uint32_t first = firsts[k];
        for (std::uint32_t i : members[k]) {
            out.radii[i] = 0.0f;
            out.ellipsoids[i] = Ellipsoid::sphere(0.0f);
        }
        const Ellipsoid& e = *fitted[k];
        out.ellipsoids[first] = e;
        out.radii[first] = static_cast<float>(
            std::cbrt(glm::length(e.axes[0]) * glm::length(e.axes[1]) * glm::length(e.axes[2])));
        out.firsts.push_back(first);
    }
    if (out.firsts.empty()) return {};
    out.cullRadii = out.radii;
    for (std::uint32_t first : out.firsts) out.cullRadii[first] = 0.0f;
    return out;
}

const Droplets& DropletCache::droplets(const core::ParticleSet& ps, std::span<const float> radii,
                                       double level, int maxAtoms) {
    return mCache.get(
        ps, [&] { return fitDroplets(ps, radii, level, maxAtoms); }, radii, level, maxAtoms);
}

}  // namespace twinrender::realtime
