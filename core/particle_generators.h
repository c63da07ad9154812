// Procedural particle sets: the shapes ball, shell and ring filled with a hcp, cubic or random
// lattice (docs/scenes.md, "Bodies"). Generators work in the body's local frame (z = the pole
// axis BodyDesc::normal) and return scene-space positions; they are deterministic and give
// bit-identical sets on every platform (plain IEEE arithmetic and sqrt only, an own PRNG).
//
// Spacing. Every lattice has one particle per s^3 of volume (number density 1/s^3). With
// s0 = (V / N)^(1/3), V the shape's volume and N = BodyDesc::particles:
//   ball:  s = s0;
//   shell: s = min(s0, t / 2), t the wall thickness: at least two layers across the wall;
//   ring:  s = t / (n k), where k s is the spacing of the lattice layers along the pole axis
//          (k = 1 for cubic and random, 2^(1/6) sqrt(2/3) = 0.9165 for hcp) and
//          n = max(2, round(t / (k s0))) the number of layers across the thickness t. The
//          layers then fill the thickness exactly, so the rendered ring is as thick as asked,
//          and there are at least two (one sheet would tear open in the level set). The count
//          is V / s^3 = N (n k s0 / t)^3: within (1 +- 1/(2n))^3 of N, and more than N for a
//          ring thinner than 1.5 k s0.
// Smoothing length h = 1.3 s unless BodyDesc::smoothing is set; volume = min(s^3, cap(h))
// with cap = maxParticleVolume (sph_kernel.h).
#pragma once

#include <cstdint>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "core/scene.h"

namespace twinrender::core {

struct GeneratedBody {
    std::vector<glm::vec3> position;  // scene units
    double spacing = 0.0;             // s: volume per particle s^3, scene units
    double h = 0.0;                   // smoothing length, scene units
    double volume = 0.0;              // colour-field volume per particle, scene units^3

    std::size_t size() const { return position.size(); }
};

// The right-handed orthonormal frame of a body: columns x, y, z with z = normalize(pole).
// x is the world x axis made orthogonal to z (the world y axis when the pole is within
// ~25 degrees of world x), y = z cross x; so the default pole (0,0,1) gives the identity.
// Throws std::invalid_argument for a zero or non-finite pole.
glm::dmat3 bodyFrame(const glm::dvec3& pole);

// Volume of the body's shape (ball, shell, ring), scene units^3. Throws InputError naming
// BodyDesc::where for invalid dimensions (non-positive radius, thickness outside (0, radius],
// inner radius not below the outer one, ...) and for shape = file.
double shapeVolume(const BodyDesc& body);

// The lattice spacing s described above.
double latticeSpacing(const BodyDesc& body);

// How many particles generateBody makes, about: the shape's volume / s^3 (exactly that many,
// rounded, for random). A thin shell or ring (two layers at least) may need far more than its
// `particles`.
double expectedParticles(const BodyDesc& body);

// Whether a body-local point (frame of bodyFrame, origin at the centre) lies inside the shape
// (closed: boundary points are inside).
bool insideShape(const BodyDesc& body, const glm::dvec3& local);

// Generates the particles of a ball, shell or ring body.
//   hcp:    hexagonal close packing (ABAB stacking), nearest-neighbour distance
//           d = 2^(1/6) s (hcp has sqrt(2)/d^3 sites per volume, = 1/s^3), basal planes
//           perpendicular to the pole axis, layer spacing d sqrt(2/3);
//   cubic:  simple cubic with edge s, axes along the body frame;
//   random: round(V / s^3) points uniform in the shape (rejection sampling in the local
//           bounding box with splitmix64 seeded by BodyDesc::seed).
// Lattice layers are symmetric about the body's mid-plane: z = (k + 1/2) * layer spacing, or
// z = k * layer spacing for a ring with an odd number of layers. Throws InputError (see
// shapeVolume) and for particles < 1 or more than 2^31 particles.
GeneratedBody generateBody(const BodyDesc& body);

// splitmix64 (Steele, Lea & Flood 2014): a tiny PRNG with the same output on every platform.
class SplitMix64 {
  public:
    explicit SplitMix64(std::uint64_t seed) : mState(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (mState += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // Uniform in [0, 1) with 53 random bits.
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

  private:
    std::uint64_t mState;
};

}  // namespace twinrender::core
