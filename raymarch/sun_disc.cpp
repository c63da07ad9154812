#include "raymarch/sun_disc.h"

#include <cmath>

#include "raymarch/ao_hemisphere.h"

namespace twinrender::raymarch {

std::vector<glm::dvec3> sunDirections(const glm::dvec3& toLight, double angularRadiusDeg,
                                      int samples) {
    if (angularRadiusDeg <= 0.0 || samples <= 1) return {toLight};
    // An orthonormal frame about toLight (Frisvad's, with the branch of Duff et al. 2017).
    const double sign = std::copysign(1.0, toLight.z);
    const double a = -1.0 / (sign + toLight.z), b = toLight.x * toLight.y * a;
    const glm::dvec3 u(1.0 + sign * toLight.x * toLight.x * a, sign * b, -sign * toLight.x);
    const glm::dvec3 v(b, sign + toLight.y * toLight.y * a, -toLight.y);
    const double oneMinusCos = 1.0 - std::cos(glm::radians(angularRadiusDeg));
    const double goldenAngle = M_PI * (3.0 - std::sqrt(5.0));
    std::vector<glm::dvec3> out;
    out.reserve(samples);
    for (int k = 0; k < samples; ++k) {
        const double cosTheta = 1.0 - (k + 0.5) / samples * oneMinusCos;
        const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
        const double phi = k * goldenAngle;
        out.push_back(glm::normalize(cosTheta * toLight +
                                     sinTheta * (std::cos(phi) * u + std::sin(phi) * v)));
    }
    return out;
}

SunDisc::SunDisc(const glm::dvec3& toLight, double angularRadiusDeg)
    : mAxis(toLight), mOneMinusCos(1.0 - std::cos(glm::radians(angularRadiusDeg))) {
    orthonormalBasis(mAxis, mU, mV);
}

glm::dvec3 SunDisc::direction(glm::dvec2 st) const {
    return coneDirection(mAxis, mU, mV, mOneMinusCos, st);
}

}  // namespace twinrender::raymarch
