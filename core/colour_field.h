// The colour field c(x) = sum_j v_j W(|x - x_j|, h_j) (M4 kernel, sph_kernel.h) over every
// particle of a set whose support covers x, all bodies included: the field whose level set the
// raymarcher renders (docs/design.md) and whose gradient gives the particle normals
// (derived_attributes.h). Evaluated at arbitrary points for the real-time renderer's models of
// the surface (realtime/field_normal.h, realtime/impostor_radius.h). Each point's sum runs in
// a fixed order, so results do not depend on the thread count.
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "core/particle_grid.h"
#include "core/particles.h"

namespace twinrender::core {

// The gradient (1/scene unit of c per scene unit) and the Hessian of c at a point.
struct FieldDerivatives {
    glm::dvec3 gradient{0.0};
    glm::dmat3 hessian{0.0};
};

class ColourField {
  public:
    // Builds the neighbour grids; `particles` must outlive the field.
    explicit ColourField(const ParticleSet& particles);

    double value(const glm::dvec3& point) const;
    FieldDerivatives derivatives(const glm::dvec3& point) const;

  private:
    const ParticleSet& mParticles;
    ParticleGrid mGrid;
};

// ColourField::derivatives at each point, in parallel.
std::vector<FieldDerivatives> colourFieldDerivatives(const ParticleSet& particles,
                                                     std::span<const glm::dvec3> points);

}  // namespace twinrender::core
