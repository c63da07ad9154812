// The particles that the fields of a bundle's rays are built from (those one bundle gather
// found), as float arrays in summation order.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "core/particles.h"

namespace twinrender::raymarch {

struct HitAttributes;

// What the field build reads of each particle, in one record, float (the field is evaluated
// in float).
struct FieldParticle {
    float x, y, z;
    float support2;  // (2h)^2
    float coef;      // v / (pi h^3)
    float invH2;     // 1 / h^2
};
std::vector<FieldParticle> makeFieldParticles(const core::ParticleSet& particles);

// Padded to whole vectors (vector_loops.h) with particles that meet no ray.
class ParticleBatch {
  public:
    struct Arrays {
        // The positions are relative to it (the first particle's): they keep float's relative
        // precision at the scale of the batch (a few h), wherever it lies.
        glm::dvec3 origin{0.0};
        std::vector<float> x, y, z, support2, coef, invH2;  // FieldParticle's members
        std::vector<float> u, v, r, g, b;  // HitAttributes' members (empty unless assigned)
        std::vector<std::uint32_t> index;  // the particle's index (0 for the padding)
    };

    // particles[prims[i]] for each i, and attributes[prims[i]] when given (for
    // averageAttributes(), hit_attributes.h).
    void assign(std::span<const std::uint32_t> prims, const std::vector<FieldParticle>& particles,
                const HitAttributes* attributes = nullptr);
    // Padding included.
    std::size_t size() const { return mArrays.index.size(); }
    const Arrays& arrays() const { return mArrays; }

  private:
    Arrays mArrays;
};

}  // namespace twinrender::raymarch
