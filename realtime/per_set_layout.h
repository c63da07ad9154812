// The layout the per-set shaders and GpuPerSet share (shaders/per_set.glsl,
// per_set_stages.glsl): the Header's byte offsets, the buffers' bindings, the texture units,
// the work groups; and the helpers per_set_gpu.cpp and per_set_programs.cpp both use. Internal
// to the GPU back end.
#pragma once

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "realtime/settings.h"
#include "realtime/shader_library.h"

namespace twinrender::realtime::per_set_layout {

// shaders/per_set.glsl: floats per particle in the Attributes buffer, and the offsets (in
// units of n floats) of each attribute.
constexpr std::size_t ATTRIBUTE_FLOATS = 21;
constexpr int MAX_LEVELS = 32;
// The Header block: 4 uints, a draw command, MAX_LEVELS levels of 64 bytes, then indirect
// dispatches (bytes): the walk list's, the next walk list's, the cell scan's, SORT's, NEAR's.
constexpr std::size_t LEVELS = 16 + 16;  // the levels' array
constexpr std::size_t WALK_DISPATCH = LEVELS + MAX_LEVELS * 64;
constexpr std::size_t NEXT_WALK_DISPATCH = WALK_DISPATCH + 16;
constexpr std::size_t SCAN_DISPATCH = NEXT_WALK_DISPATCH + 16;
constexpr std::size_t SORT_DISPATCH = SCAN_DISPATCH + 16;
constexpr std::size_t NEAR_DISPATCH = SORT_DISPATCH + 16;
// Then the levels that hold particles (LAYOUT): their count and their numbers, in order.
constexpr std::size_t USED_LEVELS = NEAR_DISPATCH + 16;
// Then LEVELS' least kernel coefficient per level, then (16-byte aligned) the sparse particles'
// list's dispatch (RADIUS_WALK's, which the droplet stages take).
constexpr std::size_t SPARSE_DISPATCH = (USED_LEVELS + 4 + 2 * MAX_LEVELS * 4 + 15) / 16 * 16;
// Then FINISH's draw command of the droplets drawn apart.
constexpr std::size_t DROPLET_DRAW = SPARSE_DISPATCH + 16;
constexpr std::size_t HEADER_BYTES = DROPLET_DRAW + 16;
constexpr std::size_t GRID_ENTRY_BYTES = 32;
constexpr unsigned GROUP = 64;        // local_size_x of the per_set_*.comp stages
constexpr unsigned REDUCED = 16;      // particles per invocation of H_MIN and LEVELS
constexpr std::size_t BLOCK = 16384;  // values per work group of scan.comp
// The coarse culling grid's directions (CullingDirections::coarseCount), per_set_cull.comp's
// COARSE_DIRECTIONS.
constexpr std::size_t COARSE_DIRECTIONS = 42;

// Every level has at most max(4 x its particles, 4096) cells.
inline std::size_t maxCells(std::size_t particles) {
    return 4 * particles + 4096 * MAX_LEVELS;
}

// At most one droplet per two particles (a droplet has two members or more).
inline std::size_t maxDroplets(std::size_t particles) {
    return std::max<std::size_t>(particles / 2, 1);
}

inline unsigned groups(std::size_t count, std::size_t per = GROUP) {
    return static_cast<unsigned>((count + per - 1) / per);
}

// Binding points of the per-set stages (shaders/per_set_stages.glsl, per_set.glsl).
enum Binding : unsigned {
    PARTICLES = 0,
    // The bodies drawn as one sphere this frame (shaders/body_mask.glsl: REPLACED; the
    // impostor programs and the gradient gather read it there too).
    BODY_MASK = 1,
    ELLIPSOIDS = 4,
    ATTRIBUTES = 5,
    HEADER = 6,
    CELLS = 7,
    CELL_OF = 8,
    ENTRIES = 9,
    SORTED = 10,
    RADII = 11,
    FLAGS = 12,
    MODELS = 13,
    DRAW_LISTS = 14,
    DIRECTIONS = 15,
    DROPLETS = 16,
    CULL_SPHERES = 17,
    WALKS = 18,
    BLOCK_SUMS = 19,    // scan.comp
    BODIES = 20,        // NORMALS
    NEAR_MASKS = 21,    // INTERIOR, CULL
    DROPLET_WORK = 22,  // RADIUS_WALK, the droplet stages
};
// Texture units of the buffer textures the walks read (shaders/per_set.glsl; the render passes
// use units 0-7).
enum TextureUnit : unsigned {
    ENTRY_TEXELS = 8,
    CELL_TEXELS = 9,
    CULL_SPHERE_TEXELS = 10,
    DIRECTION_TEXELS = 11,
    ENTRY_WORD_TEXELS = 12,
};

// shaders/per_set_stages.glsl: a droplet's first particle holds its droplet's slot + 1 in the
// flags' bits from DROPLET_SHIFT up.
constexpr unsigned DROPLET_SHIFT = 8;
// The Header block's count of droplets (uint index).
constexpr std::size_t DROPLET_COUNT = 3;

// 0: no per-particle models, 1: field normals, 2: ellipsoids (shaders/per_set_pack.comp, PACK).
inline int modelKind(const ParticleSettings& p) {
    if (p.shape == ParticleShape::Ellipsoid) return 2;
    return p.normal == NormalModel::Field ? 1 : 0;
}

// Stage `stage` of the per-set work (its file's program with the stage's #define).
const gl::Program& stageProgram(ProgramCache& programs, const char* stage);
// A culling stage (CULL, CULL_FULL) with a variant's define (or "").
const gl::Program& cullProgram(ProgramCache& programs, const char* stage, const char* variant);
// Whether GL timer queries see compute dispatches on this device (per_set_gpu.cpp).
bool timerQueriesSeeCompute(ProgramCache& programs);

}  // namespace twinrender::realtime::per_set_layout
