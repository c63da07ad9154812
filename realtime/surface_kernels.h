// The particles whose kernels can reach a surface point (realtime.particles.normal =
// "gradient"): the gradient pass adds only these, since a kernel adds nothing where its support
// (radius 2 h) stays inside the body. Most of a body's particles are deep: on a 100k-particle
// planet three in four, whose splats the pass would otherwise rasterise over the whole body.
#pragma once

#include <cstdint>
#include <vector>

#include "core/particles.h"
#include "realtime/particle_set_key.h"

namespace twinrender::realtime {

// The indices of the particles for which the colour field is at most `level` at one of 14
// points at distance 2.5 h around the particle (the 6 axis and 8 diagonal directions of the
// frame of its normal). A particle left out has the field above the level at all of them, a
// quarter of the support beyond it: the level set cannot come within its support without
// passing between those directions, where its kernel's share of the gradient is at most a few
// per cent of its peak (|w'(q)| <= 0.75 (2 - q)^2 near q = 2). Measured against every kernel:
// normals within 0.27 degrees on the LAMMPS splash, 0.05 on the planet.
std::vector<std::uint32_t> surfaceKernels(const core::ParticleSet& particles, double level);

// surfaceKernels with the last answer kept (inputs compared exactly, ParticleSetKey).
class SurfaceKernelCache {
  public:
    const std::vector<std::uint32_t>& kernels(const core::ParticleSet& particles, double level);
    bool reused() const { return mCache.reused(); }

  private:
    SetCache<std::vector<std::uint32_t>, double> mCache;
};

}  // namespace twinrender::realtime
