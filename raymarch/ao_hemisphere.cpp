#include "raymarch/ao_hemisphere.h"

#include <algorithm>
#include <cmath>

namespace twinrender::raymarch {
namespace {

// SplitMix64's finaliser (Steele, Lea and Flood 2014): a well-mixed 64-bit hash.
std::uint64_t mix(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// A number in [0, 1) from the top 53 bits of a hash.
double unit(std::uint64_t x) {
    return static_cast<double>(x >> 11) * 0x1.0p-53;
}

}  // namespace

void orthonormalBasis(const glm::dvec3& n, glm::dvec3& u, glm::dvec3& v) {
    // Frisvad's frame, with the branch of Duff et al. 2017.
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z), b = n.x * n.y * a;
    u = glm::dvec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    v = glm::dvec3(b, sign + n.y * n.y * a, -n.y);
}

glm::dvec2 jitteredStratum(int i, int j, int side, std::uint64_t seed) {
    const std::uint64_t h = mix(seed * 0x100000001b3ull + mix(std::uint64_t(i) * side + j));
    return {(i + unit(h)) / side, (j + unit(mix(h))) / side};
}

std::vector<glm::dvec3> aoDirections(const glm::dvec3& normal, int side, std::uint64_t seed) {
    glm::dvec3 u, v;
    orthonormalBasis(normal, u, v);
    std::vector<glm::dvec3> out;
    out.reserve(static_cast<std::size_t>(side) * side);
    for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j)
            out.push_back(hemisphereDirection(normal, u, v, jitteredStratum(i, j, side, seed)));
    return out;
}

glm::dvec3 hemisphereDirection(const glm::dvec3& normal, const glm::dvec3& u, const glm::dvec3& v,
                               glm::dvec2 st) {
    const double s = st.x, t = st.y;
    const double r = std::sqrt(s), phi = 2.0 * M_PI * t;
    const double z = std::sqrt(std::max(0.0, 1.0 - s));
    return glm::normalize(z * normal + r * (std::cos(phi) * u + std::sin(phi) * v));
}

glm::dvec3 coneDirection(const glm::dvec3& axis, const glm::dvec3& u, const glm::dvec3& v,
                         double oneMinusCos, glm::dvec2 st) {
    const double cosTheta = 1.0 - st.x * oneMinusCos;
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    const double phi = 2.0 * M_PI * st.y;
    return glm::normalize(cosTheta * axis + sinTheta * (std::cos(phi) * u + std::sin(phi) * v));
}

double aoStandardError(double open, int samples) {
    return std::sqrt(std::clamp(open, 0.0, 1.0) * (1.0 - std::clamp(open, 0.0, 1.0)) / samples);
}

}  // namespace twinrender::raymarch
