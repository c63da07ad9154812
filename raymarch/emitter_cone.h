// The directions the reference traces from a surface point toward one emitting body
// (light.emissive_light; core/emitters.h), and the weight of each in the irradiance estimate.
// From outside the body's bounding sphere they are uniform in solid angle over the cone the
// sphere subtends: every ray that can meet the body's surface lies in it, so no sample is spent
// elsewhere. From inside it (a point on or next to the emitter) they are cosine-weighted over the
// hemisphere. Either way the irradiance of the body is E = sum_k weight_k L_k, L_k the emitted
// radiance where ray k first meets the surface (0 where it meets another body or nothing).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace twinrender::raymarch {

struct EmitterSample {
    glm::dvec3 direction;  // unit
    // E's weight: solid angle / count x cos(theta) on the cone, pi / count on the hemisphere;
    // 0 for a direction below the surface's horizon (it is not traced).
    double weight = 0.0;
};

// The directions toward one body's bounding sphere from one point, as a map of the unit square
// (for raymarch/progressive_strata.h's rounds): the cone, or the hemisphere from inside.
class EmitterCone {
  public:
    EmitterCone(const glm::dvec3& point, const glm::dvec3& normal, const glm::dvec3& centre,
                double radius);
    glm::dvec3 direction(glm::dvec2 st) const;
    // The irradiance E is the mean over such directions of weight(direction) L, L the radiance
    // the direction sees: solidAngle cos(theta) on the cone (0 below the horizon, not traced),
    // pi on the hemisphere.
    double weight(const glm::dvec3& direction) const;

  private:
    glm::dvec3 mNormal, mAxis, mU,
        mV;  // (mU, mV, mAxis) orthonormal; the axis is the normal inside
    bool mInside = false;
    double mOneMinusCos = 0.0, mSolidAngle = 0.0;
};

// `side` x `side` directions from `point` (normal `normal`, unit) toward the sphere (centre,
// radius), stratified and jittered by `seed` as raymarch/ao_hemisphere.h's are, so that the
// estimate does not depend on the thread.
std::vector<EmitterSample> emitterSamples(const glm::dvec3& point, const glm::dvec3& normal,
                                          const glm::dvec3& centre, double radius, int side,
                                          std::uint64_t seed);

}  // namespace twinrender::raymarch
