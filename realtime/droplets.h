// Small droplets drawn as one ellipsoid each (realtime.particles.droplet_atoms). A cluster of
// a few sparse particles (a pair, a triplet ... flung off a splash) has one level-set droplet
// around all of them: a pair 1.2 h apart makes a capsule about 1.7 h long and 0.8 h wide,
// while the spheres of its particles' radii (the crossings along their normals, pointing away
// from each other, times 1.2) are two balls of 0.27 h at its ends, not even touching. No sphere
// about a particle can cover the neck without bulging far beyond the ends, so the real-time image
// loses such droplets' middles (on frame 40 of the LAMMPS splash, most of the coverage error
// of the components under 100 pixels).
//
// A droplet is a connected cluster of 2 .. droplet_atoms particles, each with fewer than
// droplet_atoms neighbours within its support (2 h), two being connected when the colour
// field at their midpoint is above the level; a cluster with an edge to any other particle
// is part of a larger body and stays spheres. Its ellipsoid is fitted to the level set: about
// the members' mean c, along the principal axes e_k of their positions' covariance, the
// field's crossings t+ and t- of the level from c along +e_k and -e_k (as the field radii find
// them, realtime/impostor_radius.h) give the semi-axis (t+ + t-) / 2 and move the centre by
// (t+ - t-) / 2 along e_k. The cluster's first particle draws the ellipsoid; the others are not
// drawn. Where the field at c is not above the level (a bent chain) or a crossing is not found
// within the cluster's support, the cluster stays spheres.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/particles.h"
#include "realtime/anisotropy.h"
#include "realtime/field_normal.h"
#include "realtime/particle_set_key.h"

namespace twinrender::realtime {

struct Droplets {
    // Per particle: the first particle of each droplet -> its ellipsoid (shift from the
    // particle's position, semi-axis vectors); every other particle -> Ellipsoid::sphere of its
    // impostor radius, 0 for the droplet's other members (not drawn).
    std::vector<Ellipsoid> ellipsoids;
    // Per particle: the impostor radius; a droplet's first particle has that of the sphere of
    // its ellipsoid's volume, its other members 0.
    std::vector<float> radii;
    // The same with every member of a droplet at 0: the spheres the occlusion culling may
    // take as occluders (a droplet's ellipsoid is not a sphere about its first particle).
    std::vector<float> cullRadii;
    // The first particles of the droplets, ascending.
    std::vector<std::uint32_t> firsts;
};

// realtime.particles.normal = "field" for a droplet's first particle: the ellipsoid's own
// normal, which the linear model (field_normal.h) holds exactly. With A's columns a_k the
// semi-axes and M = A^-T A^-1 = sum_k a_k a_k^T / |a_k|^4, the outward normal at x is along
// M (x - centre) = M (x - x_i) - M shift.
FieldNormal dropletNormalModel(const Ellipsoid& droplet);

// The droplets of the set; `radii` are the impostor radii (impostor_radius.h), `maxAtoms` the
// largest droplet (droplet_atoms; below 2: none). Empty `firsts` when there are none. The
// result does not depend on the thread count.
Droplets fitDroplets(const core::ParticleSet& particles, std::span<const float> radii, double level,
                     int maxAtoms);

// fitDroplets with the last answer kept (inputs kept and compared exactly, ParticleSetKey).
class DropletCache {
  public:
    const Droplets& droplets(const core::ParticleSet& particles, std::span<const float> radii,
                             double level, int maxAtoms);
    bool reused() const { return mCache.reused(); }

  private:
    SetCache<Droplets, std::span<const float>, double, int> mCache;
};

}  // namespace twinrender::realtime
