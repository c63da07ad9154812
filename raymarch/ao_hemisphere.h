// The directions the reference's ambient occlusion traces from a surface point (issue 27,
// "Ambient occlusion"): cosine-weighted over the hemisphere about the normal, so the fraction
// of them that reach distance R unblocked is the cosine-weighted unoccluded fraction, the
// factor the shared shading model multiplies its ambient term by.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace twinrender::raymarch {

// `side` x `side` unit directions about `normal` (a unit vector), one per stratum of the unit
// square mapped onto the disc (r = sqrt(u), phi = 2 pi v) and lifted onto the hemisphere
// (Malley's method, so the density is cos(theta) / pi). Each is jittered inside its stratum by
// a hash of (seed, stratum): fixed for a given seed (a pixel's index), so the result is the
// same on every thread count.
// Two unit vectors u, v that make (u, v, n) an orthonormal frame, for a unit n.
void orthonormalBasis(const glm::dvec3& n, glm::dvec3& u, glm::dvec3& v);

// A point of the unit square in stratum (i, j) of a side x side grid, jittered inside it by a
// hash of (seed, stratum).
glm::dvec2 jitteredStratum(int i, int j, int side, std::uint64_t seed);

std::vector<glm::dvec3> aoDirections(const glm::dvec3& normal, int side, std::uint64_t seed);

// The point st of the unit square on the disc (r = sqrt(s), phi = 2 pi t) lifted onto the
// hemisphere about `normal` ((u, v, normal) orthonormal): aoDirections' map, density
// cos(theta) / pi.
glm::dvec3 hemisphereDirection(const glm::dvec3& normal, const glm::dvec3& u, const glm::dvec3& v,
                               glm::dvec2 st);

// The point st of the unit square on the cone of directions about `axis` ((u, v, axis)
// orthonormal) whose cos(theta) reaches down to 1 - oneMinusCos: cos(theta) = 1 - s oneMinusCos,
// phi = 2 pi t, so the density is uniform in solid angle, 1 / (2 pi oneMinusCos).
glm::dvec3 coneDirection(const glm::dvec3& axis, const glm::dvec3& u, const glm::dvec3& v,
                         double oneMinusCos, glm::dvec2 st);

// The standard error of the unoccluded fraction `open` estimated from `samples` directions.
// Jittered stratification never has a larger variance than independent samples, so the
// binomial value sqrt(open (1 - open) / samples) bounds it (at most 0.5 / sqrt(samples)).
double aoStandardError(double open, int samples);

}  // namespace twinrender::raymarch
