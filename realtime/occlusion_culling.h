// Exact occlusion culling of impostor spheres that can never be seen. A sphere whose whole
// surface lies inside the union of other spheres is never the first sphere a ray meets from a
// point outside all spheres (the ray crosses its surface inside another sphere, which it
// entered earlier), so it never wins a depth test: not in the camera's G-buffer, not in the
// shadow map, from any direction. In a body of hcp or cubic lattice particles with impostors
// of about h, every particle with a full shell of neighbours is such a sphere; culling them
// leaves the surface layers and cuts the fill of the shadow and G-buffer passes several-fold
// without changing a pixel.
//
// The test is conservative: directions on the sphere are checked at the vertices of a
// geodesic grid, each required to be covered with a margin of the grid's covering radius, so
// a sphere is culled only when every point of its surface is provably covered. Coincident
// equal spheres keep the lower index.
//
// Not valid when the near plane cuts into a body (its inside would show); the renderer then
// skips culling (see renderer.cpp).
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "core/particles.h"
#include "realtime/particle_set_key.h"

namespace twinrender::realtime {

// Directions at the vertices of an icosahedron subdivided twice (162 points), and the largest
// angle from any direction to its nearest vertex (the largest angular circumradius of the
// grid's triangles): a direction covered with that margin covers every direction near it.
// The first coarseCount directions are the icosahedron subdivided once (42 points), a grid of
// its own with the wider coarseCoveringAngle.
struct CullingDirections {
    std::vector<glm::dvec3> directions;
    double coveringAngle = 0.0;  // radians
    std::size_t coarseCount = 0;
    double coarseCoveringAngle = 0.0;  // radians
};
const CullingDirections& cullingDirections();

// Indices (ascending) of the particles whose sphere, of radius radii[i], may be visible.
std::vector<std::uint32_t> unoccludedParticles(const core::ParticleSet& particles,
                                               std::span<const float> radii);

// unoccludedParticles with the last answer kept: the test depends on the spheres only, not on
// the camera or the light, so the frames of an unchanged particle set (a camera moving around
// a stored snapshot, a sweep, a benchmark) reuse it (the set and the radii kept and compared
// exactly, ParticleSetKey).
class OcclusionCuller {
  public:
    // The same indices as unoccludedParticles(particles, radii).
    const std::vector<std::uint32_t>& unoccluded(const core::ParticleSet& particles,
                                                 std::span<const float> radii);
    // Whether the last call reused the previous answer.
    bool reused() const { return mCache.reused(); }

  private:
    SetCache<std::vector<std::uint32_t>, std::span<const float>> mCache;
};

}  // namespace twinrender::realtime
