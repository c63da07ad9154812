// The particles of a scene and their derived attributes, computed once in core/ and shared
// by both renderers (docs/design.md, "Data flow"), except the particle normals: only the
// real-time renderer uses them, and it derives them as a stage of its per-set work (on the GPU
// with realtime.per_set = "gpu"). Structure of arrays, float32: what a GPU buffer and Embree
// want.
#pragma once

#include <cstdint>
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

namespace twinrender::core {

struct Scene;

struct ParticleSet {
    std::vector<glm::vec3> position;  // scene units
    std::vector<float> h;             // smoothing length, scene units, > 0
    // Colour-field volume v = m/rho, capped at 0.1 (4/3) pi h^3 (sph_kernel.h), or that cap
    // when mass or density are unknown; generated particles: min(spacing^3, cap).
    std::vector<float> volume;
    std::vector<std::uint32_t> body;      // index into SceneParticles::bodies
    std::vector<std::uint32_t> material;  // index into Scene::materials
    std::vector<glm::vec2> uv;            // texture coordinates, u in [0,1) wraps, v in [0,1]
    std::vector<glm::vec3> dudx;          // gradient of u with respect to position, 1/scene unit
    std::vector<glm::vec3> dvdx;          // gradient of v with respect to position, 1/scene unit
    // Unit, outward: -grad(colour field) normalised (deriveNormals); zero where a SceneParticles
    // says it has none.
    std::vector<glm::vec3> normal;
    std::vector<float> temperature;  // kelvin
    std::vector<glm::vec3> glow;     // blackbody emitted radiance from temperature, linear RGB

    std::size_t size() const { return position.size(); }
    // Resizes every attribute to n.
    void resize(std::size_t n);
};

struct BodyInfo {
    std::string name;
    std::uint32_t material = 0;
    glm::dvec3 center{0.0};  // origin of the body's uv frame, scene units
    glm::dmat3 frame{1.0};   // columns: local x, y, z (z = the uv pole axis)
    std::size_t begin = 0;   // particle range [begin, end) in the ParticleSet
    std::size_t end = 0;
    double meanH = 0.0;  // scene units
};

struct SceneParticles {
    ParticleSet particles;
    std::vector<BodyInfo> bodies;
    glm::dvec3 boundsMin{0.0};  // of the support spheres (position +- 2h)
    glm::dvec3 boundsMax{0.0};
    // Whether particles.normal holds the normals (given, or derived by deriveNormals); false:
    // they are zero, and a user that needs them derives them.
    bool hasNormals = true;
};

// Generates or reads every body of the scene and derives the shared attributes: uv and glow,
// not the normals (hasNormals false). Deterministic: the same scene gives the same particles
// on any thread count.
SceneParticles buildParticles(const Scene& scene);

// The normals of `particles` (derived_attributes.h's deriveNormals over its bodies); sets
// hasNormals.
void deriveNormals(SceneParticles& particles);

}  // namespace twinrender::core
