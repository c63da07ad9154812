// realtime.ao.method = "traced": ambient occlusion traced in world space (shaders/ao_traced.frag).
// From each covered pixel's surface point (the depth and normals the screen-space methods read,
// ao.depth choosing which), ao.rays cosine-weighted rays over the normal's hemisphere, each a
// segment of light.ao_radius tested against the particles' impostor spheres through a uniform
// grid; the open fraction is the share of them that meet no sphere, the quantity the reference
// traces against the implicit surface (raymarch/ao_hemisphere.h). Unlike the screen-space
// methods it sees across gaps and behind what the camera sees.
//
// The spheres: every particle's impostor sphere (impostorRadii, the radius the CPU's per-set
// work draws and the GPU's reproduces: its self-check compares them), those without a surface
// (radius 0) left out, and the spheres occlusion culling proves hidden inside their neighbours'
// union left out too: a segment from a point outside every sphere meets such a sphere only
// inside another it met first (occlusion_culling.h). Droplets' ellipsoids and body spheres
// (particles.droplet_atoms, body_sphere_pixels) are not traced: their particles' spheres stand
// for them.
//
// The grid is built here on the CPU, once per frame, by a counting sort (O(n), in particle
// order, so the same for every thread count), not on the GPU: the per-set grid of
// realtime.per_set = "gpu" (per_set_gpu.h) lists particles by their kernel's support, cells of
// 2 h, without the radii of the spheres it would have to hold, and exists only on that path.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <span>
#include <vector>

#include "core/particles.h"
#include "realtime/gl/buffer.h"
#include "realtime/impostor_radius.h"
#include "realtime/occlusion_culling.h"
#include "realtime/particle_set_key.h"
#include "realtime/settings.h"
#include "realtime/shader_library.h"

namespace twinrender::realtime {

// Spheres in a uniform grid of cubic cells: cell (x, y, z), index x + cells.x (y + cells.y z),
// lists the spheres whose bounding box overlaps it, items[cellStart[c] .. cellStart[c + 1]).
struct OcclusionGrid {
    glm::vec3 origin{0.0f};  // the grid's low corner (camera-relative)
    float side = 1.0f;       // a cell's side
    glm::ivec3 cells{1};     // cells per axis
    std::vector<std::uint32_t> cellStart{0, 0};
    std::vector<std::uint32_t> items;  // indices into spheres
    std::vector<glm::vec4> spheres;    // centre (camera-relative, subtracted in double), radius
};

// The grid of the spheres of `particles` (radii[i]; those of radius <= 0 left out), only those
// of `indices` when it is not empty, centred about `camera`. Cells have the side of the
// largest radius (at least `reach` / 64): each sphere then overlaps at most 27 cells and a
// cell lists about the spheres within two radii of it, where cells of side `reach` would each
// hold every sphere within `reach` (hundreds at the study's largest radius). A grid that would
// have more than 8 cells per sphere (and more than 4096) gets larger cells.
OcclusionGrid buildOcclusionGrid(const core::ParticleSet& particles, std::span<const float> radii,
                                 std::span<const std::uint32_t> indices, const glm::dvec3& camera,
                                 double reach);

// The spheres of a particle set (the derived normals, the impostor radii and the culling, kept
// per set as the CPU's per-set work keeps them) in a grid about the frame's camera.
class OcclusionGridCache {
  public:
    OcclusionGrid grid(const core::SceneParticles& particles, const ParticleSettings& settings,
                       const glm::dvec3& camera, double reach);

  private:
    DerivedNormalsCache mNormals;
    ImpostorRadiusCache mRadii;
    OcclusionCuller mCuller;
};

// An OcclusionGrid on the device: the shader's storage buffers (bindings 5, 6, 7) and uniforms.
struct OcclusionGridBuffers {
    gl::Buffer cellStart, items, spheres;
    glm::vec4 originSide{0.0f};
    glm::vec3 cells{1.0f};
};
OcclusionGridBuffers uploadOcclusionGrid(const OcclusionGrid& grid);

// The ao_traced.frag program for `settings` (ao.rays, ao.noise), the grid bound and its uniforms
// set, for runAmbientOcclusionPass to draw with (it sets uRadius).
const gl::Program& tracedOcclusionProgram(ProgramCache& programs, const AoSettings& settings,
                                          const OcclusionGridBuffers& grid);

// The rays' origin: moved along the normal out of the spheres it lies in, by at most
// TRACED_MAX_LIFT, then TRACED_ORIGIN_BIAS further, in the impostor radii of the pixel's
// particle (ao_traced.frag's uMaxLift, uBias).
inline constexpr double TRACED_MAX_LIFT = 1.0;
inline constexpr double TRACED_ORIGIN_BIAS = 0.25;

}  // namespace twinrender::realtime
