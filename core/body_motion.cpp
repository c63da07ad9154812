#include "core/body_motion.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "core/particle_generators.h"

namespace twinrender::core {

namespace {

// The rotation by `radians` about the unit `axis` (Rodrigues), as a matrix.
glm::dmat3 rotation(const glm::dvec3& axis, double radians) {
    const double c = std::cos(radians), s = std::sin(radians), t = 1.0 - c;
    const double x = axis.x, y = axis.y, z = axis.z;
    // Column-major: each glm::dvec3 below is a column.
    return glm::dmat3(glm::dvec3(t * x * x + c, t * x * y + s * z, t * x * z - s * y),
                      glm::dvec3(t * x * y - s * z, t * y * y + c, t * y * z + s * x),
                      glm::dvec3(t * x * z + s * y, t * y * z - s * x, t * z * z + c));
}

// A point uniform in the unit ball (rejection from the cube).
glm::dvec3 inUnitBall(SplitMix64& rng) {
    for (;;) {
        const glm::dvec3 p(2.0 * rng.uniform() - 1.0, 2.0 * rng.uniform() - 1.0,
                           2.0 * rng.uniform() - 1.0);
        if (glm::dot(p, p) <= 1.0) return p;
    }
}

}  // namespace

void applyMotion(const BodyDesc& body, double time, std::int64_t frame,
                 std::span<glm::vec3> position, double h, BodyInfo& info) {
    const double spinRate = glm::length(body.spin);  // degrees per second
    const bool turns = spinRate > 0.0 && time != 0.0;
    const glm::dvec3 shift = body.velocity * time;
    if (turns || shift != glm::dvec3(0.0)) {
        const glm::dmat3 r = turns ? rotation(body.spin / spinRate, spinRate * time * M_PI / 180.0)
                                   : glm::dmat3(1.0);
        const glm::dvec3 c = body.center;
        for (glm::vec3& p : position) p = glm::vec3(c + r * (glm::dvec3(p) - c) + shift);
        info.center = c + shift;
        info.frame = r * info.frame;
    }
    if (body.churn > 0.0) {
        SplitMix64 mix(body.seed);
        SplitMix64 rng(mix.next() ^ (static_cast<std::uint64_t>(frame) * 0xD1B54A32D192ED03ull));
        const double reach = body.churn * h;
        for (glm::vec3& p : position) p = glm::vec3(glm::dvec3(p) + reach * inUnitBall(rng));
    }
}

}  // namespace twinrender::core
