// The impostor sphere's radius per particle (realtime.particles.radius). "fixed" draws every
// particle as a sphere of radius_scale * h: right for particles inside a body, whose level set
// lies about 0.9 h beyond the outermost layer, but an isolated particle's level-set droplet is
// only about 0.13 h in radius (v W(r, h) = 0.13 with OpenSPH's volume cap), so sparse particles
// show as balls seven times too large. "field" takes the distance from the particle's centre
// along its outward normal to the level set c(x) = surface_level of the colour field
// (core/colour_field.h), capped at radius_scale * h, and 0 where the field at the centre is
// already below the level (no surface there: the particle is not drawn). A particle deep inside
// a body, the field at its centre at least interior_level, reaches the cap without the search:
// there the normal is the gradient of a field that nearly cancels, and the level set is far.
#pragma once

#include <glm/vec3.hpp>
#include <tuple>
#include <vector>

#include "core/colour_field.h"
#include "core/particles.h"
#include "realtime/particle_set_key.h"
#include "realtime/settings.h"

namespace twinrender::realtime {

// The distance from `centre` along `direction` (unit) to where the field first falls to
// `level`, at most maxDistance (found to about maxDistance * 1e-4); 0 where the field at the
// centre is not above the level.
double fieldCrossing(const core::ColourField& field, const glm::dvec3& centre,
                     const glm::dvec3& direction, double maxDistance, double level);

// radiusScale * h for each particle of the set.
std::vector<float> fixedRadii(const core::ParticleSet& particles, double radiusScale);

// One radius per particle of the set, scene units.
std::vector<float> impostorRadii(const core::ParticleSet& particles,
                                 const ParticleSettings& settings);

// impostorRadii with the last answer kept: the radii depend on the particles (position, h,
// volume, normal) and the particle settings, not on the view, so the frames of an unchanged
// set reuse them (inputs kept and compared exactly, ParticleSetKey).
class ImpostorRadiusCache {
  public:
    const std::vector<float>& radii(const core::ParticleSet& particles,
                                    const ParticleSettings& settings);
    bool reused() const { return mCache.reused(); }

  private:
    // The settings the radii depend on: radius, radius_scale, surface_level, crossing_scale,
    // interior_level.
    using RadiusSettings = std::tuple<RadiusModel, double, double, double, double>;
    SetCache<std::vector<float>, RadiusSettings> mCache;
};

}  // namespace twinrender::realtime
