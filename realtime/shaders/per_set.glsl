// The per-particle-set work on the GPU (realtime/per_set_gpu.h): the particles' raw attributes,
// the neighbour grid built from them by counting sort, and the colour field summed over it.
//
// The grid mirrors core::ParticleGrid: one uniform grid per octave of h (level
// floor(log2(h / h_min))), cells of the level's largest h, coarser where the level's box is
// sparse (at most max(4 x its particles, 4096) cells), laid out one level after another in one
// cell array. Within a cell the particles are sorted by index, so every sum over the grid runs
// in a fixed order and the results do not depend on how the driver schedules invocations.
// Distances are taken between float positions of nearby particles (exact differences), and a
// query point is an offset from its particle, so scenes far from the origin keep precision.

#include "convert.glsl"

const int MAX_LEVELS = 32;

// Offsets, in floats, of the attributes in the Attributes buffer (n = uCount particles).
#define ATTR_POSITION 0u   // 3n: x, y, z
#define ATTR_H 3u          // n
#define ATTR_VOLUME 4u     // n
#define ATTR_NORMAL 5u     // 3n
#define ATTR_BODY 8u       // n, uint bits
#define ATTR_UV 9u         // 2n
#define ATTR_DUDX 11u      // 3n
#define ATTR_DVDX 14u      // 3n
#define ATTR_GLOW 17u      // 3n
#define ATTR_MATERIAL 20u  // n, uint bits

uniform uint uCount;  // particles in the set

// WRITES_ATTRIBUTES, defined by the stages that write normals (NORMALS: derived_attributes.h's,
// where the set came without them; INTERIOR: the fallback normals of those it settles); the
// others read the attributes only.
#ifdef WRITES_ATTRIBUTES
#define ATTRIBUTES_ACCESS
#else
#define ATTRIBUTES_ACCESS readonly
#endif
// Words, not floats: the body and material indices are uint bits, which as floats are
// denormals, and GLSL lets any float operation (a load or store among them) flush a denormal
// to zero. Floats are taken from their bits (uintBitsToFloat of a normal float is exact).
layout(std430, binding = 5) ATTRIBUTES_ACCESS buffer Attributes {
    uint attributeWords[];
};

float attributeFloat(uint k) { return uintBitsToFloat(attributeWords[k]); }
vec3 attribute3(uint offset, uint i) {
    uint k = offset * uCount + 3u * i;
    return vec3(attributeFloat(k), attributeFloat(k + 1u), attributeFloat(k + 2u));
}
float attribute1(uint offset, uint i) { return attributeFloat(offset * uCount + i); }
uint attributeBits(uint offset, uint i) { return attributeWords[offset * uCount + i]; }

#ifdef WRITES_ATTRIBUTES
layout(std430, binding = 20) readonly buffer Bodies {
    vec4 bodies[];  // 2 per body: the centre; the pole axis
};
// core::deriveNormals' fallback at x, particle i's position: the radial direction from its
// body's centre, the body's pole axis at the centre.
vec3 fallbackNormal(uint i, vec3 x) {
    uint b = attributeBits(ATTR_BODY, i);
    vec3 radial = x - bodies[2u * b].xyz;
    float length_ = length(radial);
    return length_ > 0.0 ? radial / length_ : bodies[2u * b + 1u].xyz;
}
void writeNormal(uint i, vec3 n) {
    uint k = ATTR_NORMAL * uCount + 3u * i;
    attributeWords[k] = floatBitsToUint(n.x);
    attributeWords[k + 1u] = floatBitsToUint(n.y);
    attributeWords[k + 2u] = floatBitsToUint(n.z);
}
#endif

vec3 particlePosition(uint i) { return attribute3(ATTR_POSITION, i); }
float particleH(uint i) { return attribute1(ATTR_H, i); }

// Members that LEVELS updates by atomics are scalars, not components of a vector: GLSL names a
// variable, an array element or a structure member as an atomic's operand, and a swizzle is
// none of them (glslang and Mesa take one, a driver need not).
struct Level {
    uint minX, minY, minZ;  // ordered keys of the smallest x, y, z
    uint count;             // particles
    uint maxX, maxY, maxZ;  // ordered keys of the largest x, y, z
    uint hMaxBits;          // bits of the largest h
    vec4 originCell;        // the grid's corner; cell size
    ivec4 dims;             // cells along x, y, z; the level's first cell in the cell array
};

// An indirect dispatch that a list's appends build (per_set_stages.glsl's APPEND): its work
// groups, 1, 1 (glDispatchComputeIndirect's), then the list's entries.
struct Dispatch {
    uint groups, one, alsoOne;
    uint entries;
};

layout(std430, binding = 6) coherent buffer Header {
    uint hMinBits;           // the smallest h (float bits: positive floats order as uints)
    uint nearHit;            // a drawn sphere reaches into the near plane's ball (this frame)
    uint totalCells;         // cells of all levels
    uint dropletCount;       // DROPLET_FIT: the droplets fitted
    uvec4 drawParticles;     // glDrawArraysIndirect: 6 x drawn particles, 1, 6 x first, 0
    Level levels[MAX_LEVELS];
    // The walk list's dispatch (per_set_stages.glsl's appendWalk). The next list's, which a pass
    // over the walk list fills.
    Dispatch walkDispatch;
    Dispatch nextWalkDispatch;
    // LAYOUT: the work groups of the scan of the cells (scan.comp's blocks) and of SORT, 1, 1.
    uvec4 scanDispatch;
    uvec4 sortDispatch;
    // NEAR_BOUND: NEAR's work groups, 1, 1 (none where no level's box comes near the camera).
    uvec4 nearDispatch;
    // LAYOUT: the levels that hold particles, in increasing order. A walk visits these alone:
    // a loop over all MAX_LEVELS, reading each level's header to skip it, cost a walk of a
    // million particles more than its sums of one level did.
    uint usedLevels;
    uint levelList[MAX_LEVELS];
    // LEVELS: per level, the least of its particles' v / (pi h^3) (float bits), which INTERIOR
    // takes for every kernel of the level (a lower bound of the field without reading each
    // kernel's own).
    uint levelCoefficientMin[MAX_LEVELS];
    uint padding[3];  // to the 16-byte boundary per_set_gpu.cpp's SPARSE_DISPATCH keeps
    // RADIUS_WALK: the sparse particles' list's dispatch, which the droplet stages take
    // (per_set_droplets.comp's DROPLET_EDGES).
    Dispatch sparseDispatch;
    // FINISH: glDrawArraysIndirect of the droplets drawn apart (PACK's uDropletsApart),
    // the particle buffer's first: 6 x droplets, 1, 0, 0.
    uvec4 drawDroplets;
};

// A float as a uint whose order is the float's (for atomicMin / atomicMax).
uint orderedKey(float f) {
    uint u = floatBitsToUint(f);
    return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}
float fromOrderedKey(uint k) {
    return uintBitsToFloat((k & 0x80000000u) != 0u ? k & 0x7FFFFFFFu : ~k);
}

// floor(log2(h / h_min)), 0..MAX_LEVELS - 1: the exponent of the ratio's float (a NaN ratio,
// which max leaves undefined: level 0).
int levelOf(float h) {
    float ratio = h / uintBitsToFloat(hMinBits);
    int e = int(floatBitsToUint(isNanBits(ratio) ? 1.0 : max(ratio, 1.0)) >> 23) - 127;
    return clamp(e, 0, MAX_LEVELS - 1);
}

int gridCoord(float p, float origin, float invCell, int n) {
    return clampToInt(floor((p - origin) * invCell), 0, n - 1);
}

float levelInvCell(Level g) { return 1.0 / g.originCell.w; }

// The box of the level's particles' positions (LEVELS' ordered keys).
vec3 levelLow(Level g) {
    return vec3(fromOrderedKey(g.minX), fromOrderedKey(g.minY), fromOrderedKey(g.minZ));
}
vec3 levelHigh(Level g) {
    return vec3(fromOrderedKey(g.maxX), fromOrderedKey(g.maxY), fromOrderedKey(g.maxZ));
}

int cellIndex(Level g, vec3 p) {
    float inv = levelInvCell(g);
    int ix = gridCoord(p.x, g.originCell.x, inv, g.dims.x);
    int iy = gridCoord(p.y, g.originCell.y, inv, g.dims.y);
    int iz = gridCoord(p.z, g.originCell.z, inv, g.dims.z);
    return g.dims.w + (iz * g.dims.y + iy) * g.dims.x + ix;
}

// The particles sorted by cell (index order within a cell), GATHER's GridEntry records: two
// texels each, the position and 1 / h; v / (pi h^4), v / (pi h^3) (W(0) = that), the
// particle's index and its body (uint). The stages that walk the grid read it, and the
// cells' offsets, as buffer textures (per_set_gpu.cpp's texture units): Mesa's llvmpipe loads
// from a storage buffer lane by lane, a branch per lane and component, where a texel fetch is
// one gather, and a walk's loads are most of its time (NORMALS at 1M particles: 758 -> 304 ms).
// The index and body are read through an integer view of the same buffer: as float bits they
// are denormals, which a float fetch may flush to zero.
layout(binding = 8) uniform samplerBuffer uEntryTexels;
layout(binding = 9) uniform usamplerBuffer uCellTexels;  // totalCells + 1 offsets into entries
layout(binding = 12) uniform usamplerBuffer uEntryWords;  // the entries as uvec4 texels
vec4 entryPosition(uint k) { return texelFetch(uEntryTexels, int(2u * k)); }
vec4 entryCoefficients(uint k) { return texelFetch(uEntryTexels, int(2u * k + 1u)); }
// The particle of grid entry k and its body (GATHER's words z and w of the second texel).
uint entryIndex(uint k) { return texelFetch(uEntryWords, int(2u * k + 1u)).z; }
uint entryBody(uint k) { return texelFetch(uEntryWords, int(2u * k + 1u)).w; }
uint cellStart(int c) { return texelFetch(uCellTexels, c).x; }

// Row r (r = SIZE z + y) of the SIZE x SIZE x SIZE cells of level g from cell `base`: the
// grid slots of its cells that lie in the grid, [first, end) (empty outside the grid). One run
// of slots per row: the cells of a row are consecutive in the grid.
uvec2 blockRow(Level g, ivec3 base, int size, int r) {
    int x0 = max(base.x, 0), x1 = min(base.x + size - 1, g.dims.x - 1);
    ivec2 c = base.yz + ivec2(r % size, r / size);
    if (any(lessThan(c, ivec2(0))) || any(greaterThanEqual(c, g.dims.yz)) || x0 > x1)
        return uvec2(0u);
    int row = g.dims.w + (c.y * g.dims.y + c.x) * g.dims.x;
    return uvec2(cellStart(row + x0), cellStart(row + x1 + 1));
}

// Calls VISIT(k) for every grid entry k of the SIZE x SIZE x SIZE cells of level G from cell
// BASE (an ivec3; cells outside the grid left out), in the grid's order: blockRow's rows.
#define FOR_EACH_IN_BLOCK(G, BASE, SIZE, VISIT)                         \
    for (int r_ = 0; r_ < SIZE * SIZE; ++r_) {                          \
        uvec2 row_ = blockRow(G, BASE, SIZE, r_);                        \
        for (uint k_ = row_.x; k_ < row_.y; ++k_) VISIT(k_);            \
    }

// Calls VISIT(k) for every grid entry k of every level whose cells the ball of radius
// REACH(level's largest h) around POINT may reach, in a fixed order (levels, z, y rows, entries).
// Entries beyond the ball may be visited: VISIT tests the distance.
#define FOR_EACH_NEAR(POINT, REACH, VISIT)                                                     \
    for (uint u_ = 0u; u_ < usedLevels; ++u_) {                                             \
        Level g_ = levels[levelList[u_]];                                                    \
        float reach_ = REACH(uintBitsToFloat(g_.hMaxBits));                                   \
        float inv_ = levelInvCell(g_);                                                       \
        float cell_ = g_.originCell.w;                                                       \
        int z0_ = saturateToInt(floor((POINT.z - reach_ - g_.originCell.z) * inv_));         \
        int z1_ = saturateToInt(floor((POINT.z + reach_ - g_.originCell.z) * inv_));         \
        int y0_ = saturateToInt(floor((POINT.y - reach_ - g_.originCell.y) * inv_));         \
        int y1_ = saturateToInt(floor((POINT.y + reach_ - g_.originCell.y) * inv_));         \
        if (z1_ < 0 || z0_ >= g_.dims.z || y1_ < 0 || y0_ >= g_.dims.y) continue;            \
        z0_ = max(z0_, 0); z1_ = min(z1_, g_.dims.z - 1);                                    \
        y0_ = max(y0_, 0); y1_ = min(y1_, g_.dims.y - 1);                                    \
        for (int iz_ = z0_; iz_ <= z1_; ++iz_) {                                             \
            float zLo_ = g_.originCell.z + float(iz_) * cell_;                               \
            float dz_ = max(0.0, max(zLo_ - POINT.z, POINT.z - (zLo_ + cell_)));             \
            for (int iy_ = y0_; iy_ <= y1_; ++iy_) {                                         \
                float yLo_ = g_.originCell.y + float(iy_) * cell_;                           \
                float dy_ = max(0.0, max(yLo_ - POINT.y, POINT.y - (yLo_ + cell_)));         \
                float rest_ = reach_ * reach_ - dy_ * dy_ - dz_ * dz_;                       \
                if (rest_ < 0.0) continue;                                                   \
                float half_ = sqrt(rest_);                                                   \
                int x0_ = saturateToInt(floor((POINT.x - half_ - g_.originCell.x) * inv_));  \
                int x1_ = saturateToInt(floor((POINT.x + half_ - g_.originCell.x) * inv_));  \
                if (x1_ < 0 || x0_ >= g_.dims.x) continue;                                   \
                x0_ = max(x0_, 0); x1_ = min(x1_, g_.dims.x - 1);                            \
                int row_ = g_.dims.w + (iz_ * g_.dims.y + iy_) * g_.dims.x;                  \
                uint end_ = cellStart(row_ + x1_ + 1);                                       \
                for (uint k_ = cellStart(row_ + x0_); k_ < end_; ++k_) VISIT(k_);            \
            }                                                                                \
        }                                                                                    \
    }

// The M4 kernel's shape w(q) and its derivatives (core/sph_kernel.h).
float m4Shape(float q) {
    if (q >= 2.0) return 0.0;
    float a = 2.0 - q;
    return q < 1.0 ? 1.0 - 1.5 * q * q + 0.75 * q * q * q : 0.25 * a * a * a;
}
float m4ShapeDerivative(float q) {
    if (q < 1.0) return -3.0 * q + 2.25 * q * q;
    if (q < 2.0) return -0.75 * (2.0 - q) * (2.0 - q);
    return 0.0;
}
float m4ShapeSecondDerivative(float q) {
    if (q < 1.0) return -3.0 + 4.5 * q;
    if (q < 2.0) return 1.5 * (2.0 - q);
    return 0.0;
}

float supportReach(float hMax) { return 2.0 * hMax; }
