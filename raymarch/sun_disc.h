// The directions towards a sun of some angular radius: the reference traces its shadow rays
// along each of them, as today's parallel bundles, and averages the visibility, so that the
// truth has the penumbrae an extended sun casts.
#pragma once

#include <glm/glm.hpp>
#include <vector>

namespace twinrender::raymarch {

// `samples` unit directions spread evenly in solid angle over the cone of half-angle
// angularRadiusDeg about toLight (a unit vector): sample k at the cone's polar angle where
// (k + 0.5) / samples of the cap's solid angle lies inside, turned by the golden angle k times
// (Vogel's spiral, stratified in both angles). Fixed, so every pixel of every thread count
// sees the same sun. A radius of 0 gives toLight alone.
std::vector<glm::dvec3> sunDirections(const glm::dvec3& toLight, double angularRadiusDeg,
                                      int samples);

// The sun's disc as a map of the unit square, uniform in solid angle over the cone of
// half-angle angularRadiusDeg (> 0) about toLight: the directions of raymarch.sun_error's
// rounds (raymarch/progressive_strata.h), jittered per pixel where the spiral is fixed.
class SunDisc {
  public:
    SunDisc(const glm::dvec3& toLight, double angularRadiusDeg);
    glm::dvec3 direction(glm::dvec2 st) const;

  private:
    glm::dvec3 mAxis, mU, mV;
    double mOneMinusCos;
};

}  // namespace twinrender::raymarch
