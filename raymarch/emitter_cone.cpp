#include "raymarch/emitter_cone.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "raymarch/ao_hemisphere.h"

namespace twinrender::raymarch {

std::vector<EmitterSample> emitterSamples(const glm::dvec3& point, const glm::dvec3& normal,
                                          const glm::dvec3& centre, double radius, int side,
                                          std::uint64_t seed) {
    const double count = double(side) * side;
    std::vector<EmitterSample> out;
    out.reserve(static_cast<std::size_t>(count));
    const glm::dvec3 toCentre = centre - point;
    const double d = glm::length(toCentre);
    if (!(d > radius)) {
        // Inside the sphere: the cosine-weighted hemisphere, E = pi mean(L).
        for (const glm::dvec3& dir : aoDirections(normal, side, seed))
            out.push_back({dir, std::numbers::pi / count});
        return out;
    }
    // The cone about the axis to the centre: cos(theta) uniform in [cosMax, 1], the azimuth in
    // [0, 2 pi), so every direction has density 1 / solidAngle.
    const glm::dvec3 axis = toCentre / d;
    const double sinMax = radius / d;
    const double cosMax = std::sqrt(std::max(0.0, 1.0 - sinMax * sinMax));
    const double solidAngle = 2.0 * std::numbers::pi * (1.0 - cosMax);
    glm::dvec3 u, v;
    orthonormalBasis(axis, u, v);
    for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j) {
            const glm::dvec3 dir =
                coneDirection(axis, u, v, 1.0 - cosMax, jitteredStratum(i, j, side, seed));
            const double cosN = glm::dot(dir, normal);
            out.push_back({dir, cosN > 0.0 ? solidAngle / count * cosN : 0.0});
        }
    return out;
}

EmitterCone::EmitterCone(const glm::dvec3& point, const glm::dvec3& normal,
                         const glm::dvec3& centre, double radius)
    : mNormal(normal), mAxis(normal) {
    const glm::dvec3 toCentre = centre - point;
    const double d = glm::length(toCentre);
    mInside = !(d > radius);
    if (!mInside) {
        mAxis = toCentre / d;
        const double sinMax = radius / d;
        mOneMinusCos = 1.0 - std::sqrt(std::max(0.0, 1.0 - sinMax * sinMax));
        mSolidAngle = 2.0 * std::numbers::pi * mOneMinusCos;
    }
    orthonormalBasis(mAxis, mU, mV);
}

glm::dvec3 EmitterCone::direction(glm::dvec2 st) const {
    return mInside ? hemisphereDirection(mNormal, mU, mV, st)
                   : coneDirection(mAxis, mU, mV, mOneMinusCos, st);
}

double EmitterCone::weight(const glm::dvec3& direction) const {
    if (mInside) return std::numbers::pi;
    const double cosN = glm::dot(direction, mNormal);
    return cosN > 0.0 ? mSolidAngle * cosN : 0.0;
}

}  // namespace twinrender::raymarch
