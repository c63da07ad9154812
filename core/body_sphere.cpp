#include "core/body_sphere.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "core/colour_field.h"

namespace twinrender::core {

namespace {

// Directions spread evenly over the sphere (a Fibonacci lattice).
constexpr int DIRECTIONS = 64;

glm::dvec3 direction(int k) {
    const double z = 1.0 - (2.0 * k + 1.0) / DIRECTIONS;
    const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = k * std::numbers::pi * (3.0 - std::sqrt(5.0));
    return {rho * std::cos(phi), rho * std::sin(phi), z};
}

// The body's particles alone, with what the colour field reads.
ParticleSet bodyParticles(const ParticleSet& ps, const BodyInfo& body) {
    ParticleSet out;
    out.position.assign(ps.position.begin() + body.begin, ps.position.begin() + body.end);
    out.h.assign(ps.h.begin() + body.begin, ps.h.begin() + body.end);
    out.volume.assign(ps.volume.begin() + body.begin, ps.volume.begin() + body.end);
    return out;
}

// Where the field, walked inwards from the bounding radius along `dir`, first reaches `level`
// (0 if it never does): steps of a quarter of the mean h, then bisection to 1e-7 of the
// bounding radius.
double crossing(const ColourField& field, const BodyBounds& b, const glm::dvec3& dir,
                double level) {
    const double step = 0.25 * b.meanH;
    double outside = b.radius;
    // Down to the centre itself: a level set smaller than a step (one particle barely above
    // the level) is found too.
    for (double r = std::max(b.radius - step, 0.0);; r = std::max(r - step, 0.0)) {
        if (field.value(b.centre + r * dir) >= level) {
            double inside = r;
            while (outside - inside > 1e-7 * b.radius) {
                const double mid = 0.5 * (inside + outside);
                (field.value(b.centre + mid * dir) >= level ? inside : outside) = mid;
            }
            return 0.5 * (inside + outside);
        }
        if (r == 0.0) return 0.0;
        outside = r;
    }
}

}  // namespace

BodyBounds bodyBounds(const ParticleSet& ps, const BodyInfo& body) {
    BodyBounds out;
    if (body.end <= body.begin) return out;
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    double hSum = 0.0;
    for (std::size_t i = body.begin; i < body.end; ++i) {
        const glm::dvec3 p(ps.position[i]);
        lo = glm::min(lo, p - 2.0 * double(ps.h[i]));
        hi = glm::max(hi, p + 2.0 * double(ps.h[i]));
        hSum += ps.h[i];
    }
    out.centre = 0.5 * (lo + hi);
    for (std::size_t i = body.begin; i < body.end; ++i) {
        const double d = glm::length(glm::dvec3(ps.position[i]) - out.centre);
        out.radius = std::max(out.radius, d + 2.0 * double(ps.h[i]));
        out.particles = std::max(out.particles, d);
    }
    out.meanH = hSum / double(body.end - body.begin);
    return out;
}

namespace {

double levelSetRadius(const ParticleSet& ps, const BodyInfo& body, const BodyBounds& bounds,
                      double surfaceLevel) {
    const ParticleSet own = bodyParticles(ps, body);
    const ColourField field(own);
    double squares = 0.0;
    for (int k = 0; k < DIRECTIONS; ++k) {
        const double r = crossing(field, bounds, direction(k), surfaceLevel);
        squares += r * r;
    }
    return std::sqrt(squares / DIRECTIONS);
}

}  // namespace

double levelSetRadius(const ParticleSet& ps, const BodyInfo& body, double surfaceLevel) {
    if (body.end <= body.begin) return 0.0;
    return levelSetRadius(ps, body, bodyBounds(ps, body), surfaceLevel);
}

std::vector<BodySphere> bodySpheres(const SceneParticles& particles, double surfaceLevel) {
    std::vector<BodySphere> out;
    const ParticleSet& ps = particles.particles;
    for (std::uint32_t b = 0; b < particles.bodies.size(); ++b) {
        const BodyInfo& info = particles.bodies[b];
        if (info.end <= info.begin) continue;
        const BodyBounds bounds = bodyBounds(ps, info);
        glm::dvec3 glow(0.0);
        for (std::size_t i = info.begin; i < info.end; ++i) glow += glm::dvec3(ps.glow[i]);
        out.push_back({.body = b,
                       .centre = bounds.centre,
                       .radius = levelSetRadius(ps, info, bounds, surfaceLevel),
                       .reach = bounds.radius,
                       .glow = glm::vec3(glow / double(info.end - info.begin))});
    }
    return out;
}

}  // namespace twinrender::core
