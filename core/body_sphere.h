// The sphere a body's particles make: the bounds of its supports (the emitting bodies' light
// cones and point lights, core/emitters.h) and the sphere of its level set (the real-time
// renderer's whole-body sphere, realtime.particles.body_sphere_pixels: a far body drawn as one
// analytic sphere instead of its particles).
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "core/particles.h"

namespace twinrender::core {

struct BodyBounds {
    // The middle of the bounding box of the body's support spheres (position +- 2h).
    glm::dvec3 centre{0.0};
    double radius = 0.0;     // a sphere about `centre` holding every support sphere
    double particles = 0.0;  // the particle centres' largest distance from `centre`
    double meanH = 0.0;      // the particles' mean smoothing length
};

// The bounds of `body`'s particles (all zero for a body without particles).
BodyBounds bodyBounds(const ParticleSet& particles, const BodyInfo& body);

struct BodySphere {
    std::uint32_t body = 0;  // index into SceneParticles::bodies
    glm::dvec3 centre{0.0};  // BodyBounds::centre
    // The root mean square of the distances from `centre` at which the body's own colour field
    // falls to the surface level, over 64 directions: the sphere of the level set's mean
    // cross-section, so a far body's coverage is kept whichever way it is seen. 0 where the
    // field nowhere reaches the level.
    double radius = 0.0;
    double reach = 0.0;    // BodyBounds::radius: every support sphere lies within it
    glm::vec3 glow{0.0f};  // the particles' mean blackbody glow, linear RGB
};

// The radius of the sphere a body's level set lies about: the root mean square of the distances
// from bodyBounds' centre at which the body's own colour field (its particles alone) falls to
// `surfaceLevel`, walked inwards along 64 directions spread evenly over the sphere (a direction
// along which it never reaches the level counts 0). 0 for a body without particles. A packed
// ball's level set lies about 0.9 h above its outermost particles, not at them.
double levelSetRadius(const ParticleSet& particles, const BodyInfo& body, double surfaceLevel);

// The level-set sphere of every body with particles, in body order. The body's own particles
// alone make its field, so a neighbour touching it does not widen it.
std::vector<BodySphere> bodySpheres(const SceneParticles& particles, double surfaceLevel);

}  // namespace twinrender::core
