// The per-particle-set work on the GPU (realtime/per_set_gpu.h), one stage per #define: the
// grid (INIT, H_MIN, LEVELS, LAYOUT, COUNT, SCATTER, SORT, GATHER), the particle normals where
// the set came without them (NORMALS), the answers per particle
// (INTERIOR, RADIUS, KERNELS, CULL, FIELD_NORMAL, ANISOTROPY), the small droplets (DROPLET_EDGES,
// DROPLET_CLUSTERS, DROPLET_LINKS, DROPLET_FIT) and the frame's draw lists (NEAR,
// MARK, PACK, FINISH). Every stage but LAYOUT and FINISH runs one invocation per particle (or
// cell, or entry of a list).
#if defined(NORMALS) || defined(RADIUS) || defined(RADIUS_WALK) || defined(KERNELS) || \
    defined(CULL) || defined(CULL_FULL) || defined(FIELD_NORMAL) || defined(ANISOTROPY) ||   \
    defined(CULL_SPHERES) || defined(INTERIOR) || defined(DROPLET_EDGES) || defined(DROPLET_FIT)
#define GRID_READ
#endif
#include "per_set.glsl"

#if defined(LAYOUT) || defined(FINISH) || defined(INIT)
layout(local_size_x = 32) in;
#else
layout(local_size_x = 64) in;
#endif

uint invocation() { return gl_GlobalInvocationID.x; }

#if defined(COUNT) || defined(SCATTER) || defined(SORT) || defined(GATHER)
layout(std430, binding = 7) buffer Cells {
    uint cellStart[];  // COUNT: counts; after the scan: offsets (totalCells + 1)
};
layout(std430, binding = 8) buffer CellOf {
    uint cellOf[];  // per particle: its cell; SCATTER: then the fill count per cell after n
};
layout(std430, binding = 10) buffer Sorted {
    uint sorted[];  // particle indices by cell
};
#endif

#if defined(RADIUS) || defined(RADIUS_WALK) || defined(KERNELS) || defined(CULL) || \
    defined(FIELD_NORMAL) || defined(ANISOTROPY) || defined(NEAR) || defined(MARK) ||     \
    defined(PACK) || defined(CULL_SPHERES) || defined(INTERIOR) || defined(INTERIOR_DRAWN) || \
    defined(DROPLET_FIT)
layout(std430, binding = 11) buffer Radii {
    float radii[];
};
#endif

// flags: bit 1: hidden (occlusion_culling.h); bit 2: settled by INTERIOR (its normal is not
// derived until it may be drawn); bit 3: sparse (droplets.h: a surface, fewer than
// droplet_atoms neighbours); bit 4: a sparse particle with an edge to one that is not.
const uint HIDDEN = 2u, INTERIOR_BIT = 4u, SPARSE_BIT = 8u, JOINS_BIT = 16u;
#if defined(CULL) || defined(CULL_FULL) || defined(MARK) || defined(NEAR) || defined(KERNELS) || \
    defined(PACK) || defined(CULL_SPHERES) || defined(INTERIOR) || defined(INTERIOR_DRAWN) ||  \
    defined(RADIUS_WALK) || defined(DROPLET_EDGES) || defined(DROPLET_CLUSTERS) ||           \
    defined(DROPLET_FIT)
layout(std430, binding = 12) buffer Flags {
    uint flags[];  // CULL writes bit 1 of its own particle's flags only
};
#endif

// A droplet's first particle: its slot + 1 in the flags from bit 8 (0: not a droplet's), and
// per droplet its ellipsoid (GpuEllipsoid, 3 vec4 from 3 slot: the droplets' draw reads them
// there) and, after the ellipsoids of the most droplets a set may hold (one per two
// particles), its field normal model (FieldNormal, 3 vec4 from dropletModel(slot)).
#if defined(CULL_SPHERES) || defined(NEAR) || defined(KERNELS) || defined(PACK) || \
    defined(INTERIOR_DRAWN) || defined(MARK)
uint dropletSlot(uint i) { return flags[i] >> 8; }
#endif
#if defined(PACK) || defined(DROPLET_FIT)
uint dropletModel(uint slot) { return 3u * (max(uCount / 2u, 1u) + slot); }
#endif
#if defined(KERNELS) || defined(PACK)
layout(std430, binding = 16) readonly buffer Droplets {
    vec4 droplets[];
};
#endif

#if defined(FIELD_NORMAL) || defined(ANISOTROPY) || defined(PACK) || defined(KERNELS)
// Three vec4 per particle: FieldNormal (outward, -H diagonal, -H off-diagonal) or the ellipsoid
// (GpuEllipsoid: axes in xyz, the centre's shift in w).
layout(std430, binding = 13) buffer Models {
    vec4 models[];
};
#endif

// The invocations a long pass takes, appended by the pass before it and dispatched indirectly
// (the Header's walkDispatch: work groups, 1, 1, entries): NORMALS and RADIUS the particles
// INTERIOR leaves, NORMALS also those of INTERIOR's that INTERIOR_DRAWN lists, CULL_FULL the
// grid slots CULL's coarse test leaves, KERNELS and PACK the particles MARK draws; and the
// next list (nextWalkDispatch, after the first in the Walks buffer), which a pass over the walk
// list fills: RADIUS_WALK the particles RADIUS's early exit leaves. One dispatch over them alone
// keeps the lanes busy, where in the particles' order (or the list's) they would be a few lanes
// of many vectors, each vector paying the long loops (RADIUS_WALK over RADIUS's whole list,
// with the lanes RADIUS settled idle, took 65 ms at 1M particles; over the next list, 45 ms).
// Appends VALUE to a list, LIST[AT + entry], dispatched indirectly by DISPATCH (work groups,
// 1, 1, entries). A macro: GLSL hands no buffer member to an atomic through a parameter.
#define APPEND(DISPATCH, LIST, AT, VALUE)                               \
    {                                                                   \
        uint entry_ = atomicAdd(DISPATCH.w, 1u);                        \
        if (entry_ % gl_WorkGroupSize.x == 0u) atomicAdd(DISPATCH.x, 1u); \
        LIST[(AT) + entry_] = (VALUE);                                  \
    }
#if defined(RADIUS) || defined(RADIUS_WALK) || defined(CULL) || defined(CULL_FULL) || \
    defined(MARK) || defined(KERNELS) || defined(INTERIOR) || defined(INTERIOR_DRAWN) ||   \
    defined(NORMALS) || defined(PACK)
layout(std430, binding = 18) buffer Walks {
    uint walkList[];
};
void appendWalk(uint value) APPEND(walkDispatch, walkList, 0u, value)
void appendNextWalk(uint value) APPEND(nextWalkDispatch, walkList, uCount, value)
#endif

// The droplet stages' work (droplets.h), four runs of uCount words: the sparse particles'
// list, which RADIUS_WALK appends (sparseDispatch); per sparse particle its parent in the
// clusters' union-find (DROPLET_CLUSTERS: its root; DROPLET_LINKS: the next member of its
// droplet); per root its cluster's size and JOINS_BIT (DROPLET_CLUSTERS); per root of a
// droplet the first of its members' list (DROPLET_LINKS). RADIUS_WALK sets a sparse particle's
// words; the others are never read.
#if defined(RADIUS_WALK) || defined(DROPLET_EDGES) || defined(DROPLET_CLUSTERS) || \
    defined(DROPLET_LINKS) || defined(DROPLET_FIT)
layout(std430, binding = 22) coherent buffer DropletWork {
    uint dropletWork[];
};
const uint NO_MEMBER = 0xFFFFFFFFu;
#define PARENT(i) dropletWork[uCount + (i)]
#define CLUSTER(i) dropletWork[2u * uCount + (i)]
#define MEMBERS(i) dropletWork[3u * uCount + (i)]
void appendSparse(uint i) {
    APPEND(sparseDispatch, dropletWork, 0u, i)
    PARENT(i) = i;
    CLUSTER(i) = 0u;
    MEMBERS(i) = NO_MEMBER;
}
// The sparse particle of this invocation (NO_MEMBER past the list).
uint sparseParticle() {
    return invocation() < sparseDispatch.w ? dropletWork[invocation()] : NO_MEMBER;
}
#endif

// ---- The grid ----

#ifdef INIT
void main() {
    uint L = invocation();
    if (L == 0u) {
        hMinBits = 0x7F800000u;  // +inf
        totalCells = 0u;
        nearHit = 0u;
    }
    if (L < uint(MAX_LEVELS)) {
        levels[L].minKey = uvec4(0xFFFFFFFFu, 0xFFFFFFFFu, 0xFFFFFFFFu, 0u);
        levels[L].maxKey = uvec4(0u);
        levelCoefficientMin[L] = 0x7F800000u;  // +inf
    }
}
#endif

// H_MIN and LEVELS: each invocation takes PER_INVOCATION particles (a stride of all the
// invocations apart, so neighbouring invocations read neighbouring particles), folds them in
// its registers and updates the Header once per value (per level run for LEVELS): an atomic
// per particle and value, on the same few words, would cost more than the rest of the grid.
const uint PER_INVOCATION = 16u;  // per_set_gpu.cpp's REDUCED
uint stride() { return gl_NumWorkGroups.x * gl_WorkGroupSize.x; }

#ifdef H_MIN
void main() {
    uint least = 0x7F800000u;  // +inf
    for (uint k = 0u, i = invocation(); k < PER_INVOCATION && i < uCount; ++k, i += stride())
        least = min(least, floatBitsToUint(particleH(i)));
    atomicMin(hMinBits, least);
}
#endif

#if defined(LEVELS) || defined(GATHER)
// A particle's kernel at its centre, v / (pi h^3) = W(0), and the coefficient of its
// derivatives, v / (pi h^4), computed in double and rounded once.
vec2 kernelCoefficients(uint i) {
    double h = double(particleH(i));
    double v = double(attribute1(ATTR_VOLUME, i));
    const double PI = 3.14159265358979323846LF;
    return vec2(float(v / (PI * h * h * h * h)), float(v / (PI * h * h * h)));
}
#endif

#ifdef LEVELS
void addToLevel(int L, uvec4 lo, uvec4 hi, uint coefficientMin) {
    atomicMin(levels[L].minKey.x, lo.x);
    atomicMin(levels[L].minKey.y, lo.y);
    atomicMin(levels[L].minKey.z, lo.z);
    atomicAdd(levels[L].minKey.w, lo.w);
    atomicMax(levels[L].maxKey.x, hi.x);
    atomicMax(levels[L].maxKey.y, hi.y);
    atomicMax(levels[L].maxKey.z, hi.z);
    atomicMax(levels[L].maxKey.w, hi.w);
    atomicMin(levelCoefficientMin[L], coefficientMin);
}
void main() {
    int L = -1;  // the level of the run of particles folded so far
    uvec4 lo = uvec4(0u), hi = uvec4(0u);  // their smallest keys, count; largest keys, h
    uint coefficientMin = 0u;              // their least v / (pi h^3) (float bits)
    for (uint k = 0u, i = invocation(); k < PER_INVOCATION && i < uCount; ++k, i += stride()) {
        float h = particleH(i);
        int level = levelOf(h);
        vec3 p = particlePosition(i);
        uvec3 key = uvec3(orderedKey(p.x), orderedKey(p.y), orderedKey(p.z));
        uint coefficient = floatBitsToUint(kernelCoefficients(i).y);
        if (level != L) {
            if (L >= 0) addToLevel(L, lo, hi, coefficientMin);
            L = level;
            lo = uvec4(key, 0u);
            hi = uvec4(key, 0u);
            coefficientMin = coefficient;
        }
        lo = uvec4(min(lo.xyz, key), lo.w + 1u);
        hi = uvec4(max(hi.xyz, key), max(hi.w, floatBitsToUint(h)));
        coefficientMin = min(coefficientMin, coefficient);
    }
    if (L >= 0) addToLevel(L, lo, hi, coefficientMin);
}
#endif

#ifdef LAYOUT
// One invocation: each level's cells (core::ParticleGrid's sizes), one level after another.
void main() {
    if (invocation() != 0u) return;
    int first = 0;
    uint used = 0u;
    for (int L = 0; L < MAX_LEVELS; ++L) {
        Level g = levels[L];
        if (g.minKey.w == 0u) {
            levels[L].dims = ivec4(1, 1, 1, first);
            continue;
        }
        levelList[used++] = uint(L);
        vec3 lo = levelLow(g), hi = levelHigh(g);
        vec3 extent = hi - lo;
        float maxCells = max(4.0 * float(g.minKey.w), 4096.0);
        float cell = uintBitsToFloat(g.maxKey.w);
        vec3 n;
        for (int k = 0; k < 200; ++k) {
            n = floor(extent / cell) + 1.0;
            float total = n.x * n.y * n.z;
            if (total <= maxCells) break;
            cell *= max(1.01, pow(total / maxCells, 1.0 / 3.0));
        }
        levels[L].originCell = vec4(lo, cell);
        levels[L].dims = ivec4(ivec3(n), first);
        first += int(n.x * n.y * n.z);
    }
    totalCells = uint(first);
    usedLevels = used;
    scanDispatch = uvec4((totalCells + 16383u) / 16384u, 1u, 1u, 0u);  // scan.comp BLOCK
    sortDispatch = uvec4((totalCells + 63u) / 64u, 1u, 1u, 0u);  // SORT's work groups of 64
}
#endif

#ifdef COUNT
void main() {
    uint i = invocation();
    if (i >= uCount) return;
    // A local copy: a member of the coherent Header block passed to a parameter without that
    // qualifier is a compile error on NVIDIA's compiler (C1317).
    Level g = levels[levelOf(particleH(i))];
    uint c = uint(cellIndex(g, particlePosition(i)));
    cellOf[i] = c;
    atomicAdd(cellStart[c], 1u);
}
#endif

#ifdef SCATTER
void main() {
    uint i = invocation();
    if (i >= uCount) return;
    uint c = cellOf[i];
    uint slot = atomicAdd(cellOf[uCount + c], 1u);
    sorted[cellStart[c] + slot] = i;
}
#endif

#ifdef SORT
// The scatter's order within a cell depends on scheduling: sort each cell by index (Shell sort
// with Ciura's gaps: insertion sort for the usual few particles, no quadratic cost for a
// crowded cell of a sparse level).
const uint GAPS[8] = uint[](701u, 301u, 132u, 57u, 23u, 10u, 4u, 1u);
void main() {
    uint c = invocation();
    if (c >= totalCells) return;
    uint begin = cellStart[c], end = cellStart[c + 1u];
    if (end - begin < 2u) return;  // most cells
    int first = 7;  // the largest gap below the count
    while (first > 0 && GAPS[first - 1] < end - begin) --first;
    for (int g = first; g < 8; ++g) {
        uint gap = GAPS[g];
        for (uint k = begin + gap; k < end; ++k) {
            uint v = sorted[k];
            uint j = k;
            for (; j >= begin + gap && sorted[j - gap] > v; j -= gap) sorted[j] = sorted[j - gap];
            sorted[j] = v;
        }
    }
}
#endif

#ifdef GATHER
// Two uvec4 per entry (per_set.glsl): the floats' bits, then the index and body as they are.
layout(std430, binding = 9) writeonly buffer Entries {
    uvec4 entryWords[];
};
void main() {
    uint k = invocation();
    if (k >= uCount) return;
    uint i = sorted[k];
    entryWords[2u * k] = floatBitsToUint(
        vec4(particlePosition(i), float(1.0LF / double(particleH(i)))));
    entryWords[2u * k + 1u] =
        uvec4(floatBitsToUint(kernelCoefficients(i)), i, attributeBits(ATTR_BODY, i));
}
#endif

// ---- Answers per particle ----

// A unit normal and two tangents (surface_kernels.cpp's frame).
mat3 normalFrame(vec3 n) {
    n = length(n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0);
    vec3 helper = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    vec3 t1 = normalize(cross(n, helper));
    return mat3(t1, cross(n, t1), n);
}

#if defined(RADIUS) || defined(RADIUS_WALK)
// impostor_radius.cpp: the distance along the normal to the level set (0 where the field at
// the centre is not above it), at most radius_scale h; "fixed" (uFixed): radius_scale h.
//
// Most particles lie inside a body: the field is above the level at the centre and at both
// early-exit samples (radius_scale h and half of it), so the radius is radius_scale h (times
// crossing_scale, capped), whatever the sums' exact values. Kernels are never negative, so a
// sum over some of the neighbours is a lower bound of the field, in float too (adding a
// non-negative float never lowers a sum): the 3 x 3 x 3 cells of the particle's own level
// about the samples' midpoint usually settle such a particle (of the 45k particles INTERIOR
// leaves on the 1M planet, 2 x 2 x 2 cells settled 11k, 3 x 3 x 3 settle 25k: the radius
// stages 150 -> 137 ms). The others take the full sums,
// each over the whole neighbourhood in the grid's fixed order, the three samples in one walk,
// then, where the early exit fails, walks of eight samples each (below).
float samplesReach_;
float samplesReach(float hMax) { return supportReach(hMax) + samplesReach_; }
// The field at centre + (t0 + k step) n, k = 1..8, in one walk about their middle (each sum
// in the grid's fixed order).
void fieldSamples(vec3 centre, vec3 n, float t0, float step, out float values[8]) {
    vec3 offsets[8];
    for (int k = 0; k < 8; ++k) {
        values[k] = 0.0;
        offsets[k] = (t0 + float(k + 1) * step) * n;
    }
    samplesReach_ = 4.0 * step;
    vec3 middle = centre + (t0 + 4.5 * step) * n;
#define ADD_EIGHT(k)                                                                \
    {                                                                               \
        vec4 e = entryPosition(k);                                                  \
        vec3 d = e.xyz - centre;                                                    \
        float c = entryCoefficients(k).x / e.w;                                     \
        for (int s = 0; s < 8; ++s) values[s] += c * m4Shape(length(d - offsets[s]) * e.w); \
    }
    FOR_EACH_NEAR(middle, samplesReach, ADD_EIGHT)
#undef ADD_EIGHT
}

uniform float uRadiusScale, uCrossingScale, uLevel, uInteriorLevel;
uniform int uFixed;
// droplets.h's sparse test where > 0: a particle with a surface and fewer than this many
// neighbours within 2 h is listed for the droplet stages (appendSparse).
uniform int uDropletAtoms;
float countReach_, halfCap_;
// About the samples' midpoint: every kernel that reaches a sample, every neighbour within 2 h.
float walkReach(float hMax) { return max(supportReach(hMax), countReach_) + halfCap_; }

// The field at the centre, half-way and at the cap, and the particles within 2 h, the particle
// itself among them: RADIUS_WALK visits it once (it lies within walkReach), so its neighbours
// are one fewer; the early exit's 3 x 3 x 3 cells hold it too unless radius_scale is large, and
// a count one short there only leaves the particle to the walk.
#define ADD_SAMPLES(k)                                            \
    {                                                             \
        vec4 e = entryPosition(k);                                \
        vec3 d = e.xyz - centre;                                  \
        float c = entryCoefficients(k).x / e.w;                   \
        atCentre += c * m4Shape(length(d) * e.w);                 \
        atHalf += c * m4Shape(length(d - halfway) * e.w);         \
        atCap += c * m4Shape(length(d - cap) * e.w);              \
        if (dot(d, d) < countReach2) ++neighbours;                \
    }

void main() {
#ifdef RADIUS_WALK
    uint t = invocation();
    if (t >= nextWalkDispatch.w) return;
    uint i = walkList[uCount + t];  // left by RADIUS's early exit
#else
    // "fixed": every particle; "field": those INTERIOR left, its list.
    uint i;
    if (uFixed != 0) {
        i = invocation();
        if (i >= uCount) return;
    } else {
        uint t = invocation();
        if (t >= walkDispatch.w) return;
        i = walkList[t];
    }
#endif
    float h = particleH(i);
    float maxRadius = uRadiusScale * h;
    if (uFixed != 0) {
        radii[i] = maxRadius;
        return;
    }
    vec3 centre = particlePosition(i);
    vec3 n = normalize(attribute3(ATTR_NORMAL, i));
    const float PI = 3.14159265358979;
    float own = attribute1(ATTR_VOLUME, i) / (PI * h * h * h);
    float ownBound = own * (1.0 + 1e-4);  // at or below: alone in its support
    vec3 halfway = (0.5 * maxRadius) * n, cap = maxRadius * n;
    float countReach2 = uDropletAtoms > 0 ? 4.0 * h * h : 0.0;
    float atCentre = 0.0, atHalf = 0.0, atCap = 0.0;
    int neighbours = 0;
#ifndef RADIUS_WALK
    {
        Level g = levels[levelOf(h)];
        float inv = levelInvCell(g);
        ivec3 base = ivec3(floor((centre + 0.5 * cap - g.originCell.xyz) * inv)) - ivec3(1);
        FOR_EACH_IN_BLOCK(g, base, 3, ADD_SAMPLES)
    }
    if (uDropletAtoms > 0) --neighbours;  // itself
    if (atCentre > max(uLevel, ownBound) &&
        (atCentre >= uInteriorLevel || (atHalf > uLevel && atCap > uLevel)) &&
        neighbours >= uDropletAtoms) {
        radii[i] = min(maxRadius, uCrossingScale * maxRadius);
        return;
    }
    appendNextWalk(i);  // left to RADIUS_WALK
#else
    // One walk for the field at the centre and at the 8 samples k maxRadius / 8 (k = 1..8) of the
    // bisection's first pass, half-way and the cap among them (the same offsets, so the same
    // sums as three separate walks would give).
    countReach_ = uDropletAtoms > 0 ? 2.0 * h : 0.0;
    halfCap_ = 0.5 * maxRadius;
    vec3 middle = centre + 0.5 * cap;
    float step = maxRadius / 8.0;
    float values[8];
    vec3 offsets[8];
    for (int k = 0; k < 8; ++k) {
        values[k] = 0.0;
        offsets[k] = (0.0 + float(k + 1) * step) * n;  // fieldSamples' offsets from 0
    }
#define ADD_NINE(k)                                                                         \
    {                                                                                       \
        vec4 e = entryPosition(k);                                                          \
        vec3 d = e.xyz - centre;                                                            \
        float c = entryCoefficients(k).x / e.w;                                             \
        atCentre += c * m4Shape(length(d) * e.w);                                           \
        for (int s = 0; s < 8; ++s) values[s] += c * m4Shape(length(d - offsets[s]) * e.w); \
        if (dot(d, d) < countReach2) ++neighbours;                                          \
    }
    FOR_EACH_NEAR(middle, walkReach, ADD_NINE)
#undef ADD_NINE
    if (uDropletAtoms > 0) --neighbours;  // itself
    atHalf = values[3];
    atCap = values[7];
    float crossing = 0.0;
    bool alone = atCentre <= ownBound;
    if (atCentre > uLevel) {
        if ((!alone && atCentre >= uInteriorLevel) || (atCap > uLevel && atHalf > uLevel)) {
            crossing = maxRadius;
        } else {
            // The first of the 8 samples not above the level brackets the crossing; two more
            // walks of 8 samples each narrow the bracket 9-fold, to maxRadius / 648, and the
            // crossing is interpolated linearly within it (the CPU path bisects to
            // maxRadius / 8192; the two agree within 1e-4 h).
            // Once crossing_scale times the bracket's inner end reaches the cap, the radius is
            // the cap wherever the crossing lies beyond: the bracket is not narrowed further.
            float inside = 0.0, outside = -1.0, atInside = atCentre, atOutside = 0.0;
            float scale = alone ? 1.0 : uCrossingScale;
            bool capped = false;
            for (int pass = 0; pass < 3 && !(pass > 0 && outside < 0.0) && !capped; ++pass) {
                if (pass > 0) fieldSamples(centre, n, inside, step, values);
                int first = 8;
                for (int k = 7; k >= 0; --k)
                    if (!(values[k] > uLevel)) first = k;
                if (first == 8) {
                    if (pass == 0) break;  // above at every sample: the cap
                    // Between the last sample and the bracket's outer end.
                    inside += 8.0 * step;
                    atInside = values[7];
                } else {
                    // values[] indexed by constants alone (a dynamic index keeps the array in
                    // memory, and every sum of the walks above loads and stores it).
                    for (int k = 0; k < 8; ++k) {
                        if (k == first - 1) atInside = values[k];
                        if (k == first) atOutside = values[k];
                    }
                    if (first > 0) inside += float(first) * step;
                    outside = inside + step;
                }
                step = (outside - inside) / 9.0;
                capped = scale * inside >= maxRadius;
            }
            if (outside < 0.0 || capped)
                crossing = maxRadius;
            else
                crossing = inside + (outside - inside) * clamp((atInside - uLevel) /
                                                                   max(atInside - atOutside, 1e-30),
                                                               0.0, 1.0);
        }
    }
    float radius = min(maxRadius, (alone ? 1.0 : uCrossingScale) * crossing);
    radii[i] = radius;
    if (radius > 0.0 && neighbours < uDropletAtoms) {
        flags[i] |= SPARSE_BIT;
        appendSparse(i);
    }
#endif
}
#undef ADD_SAMPLES
#endif

// The culling's near shell (CULL's coarse test below), found by INTERIOR's walk over the same
// 3 x 3 x 3 cells: per grid slot, the other entries of those cells within NEAR_SHELL times the
// particle's cap (its radius is at most that) as bits in the order visited, the first 128. CULL
// then makes their caps without a walk of its own (at 1M particles INTERIOR 83 -> 102 ms,
// CULL's coarse test 150 -> 101 ms). Two masks: the inner shell (within INNER_SHELL caps, the
// nearest neighbours), then the rest, which CULL reads only where the inner caps leave a
// direction uncovered: on the 1M planet the inner caps alone cover every sphere the coarse test
// hides (951k), and the coarse test takes 12 caps a sphere where it took 18 (85 -> 68 ms,
// INTERIOR +6 ms).
#if defined(INTERIOR) || defined(CULL) || defined(CULL_FULL)
const float NEAR_SHELL = 1.4, INNER_SHELL = 1.1;  // caps
#endif
#if defined(INTERIOR) || defined(CULL)
const uint NEAR_MASK_BITS = 128u;
layout(std430, binding = 21) buffer NearMasks {
    uvec4 nearMasks[];  // per slot the inner shell, then the outer: bit t % 32 of word t / 32
                        // for the t-th entry visited
};
#endif

#ifdef INTERIOR
// impostor_radius.cpp's interior_level, before any normal: most particles of a body lie deep
// inside it, where the field at the centre is far above the level and the normal is the
// gradient of a field that nearly cancels. A lower bound of the field at the centre, the sum
// over the 3 x 3 x 3 cells of the particle's own level about its cell (kernels are never
// negative), at or above interior_level, surface_level and the particle's own kernel's peak
// settles it: its radius is the cap, and it takes the fallback normal (NORMALS': the radial
// direction from its body's centre, the pole axis at the centre) until INTERIOR_DRAWN finds it
// may be drawn. It also needs droplet_atoms neighbours within 2 h in those cells (the
// droplets' sparse test; a lower bound too). The others are listed for NORMALS, RADIUS and
// RADIUS_WALK, which apply the same rule to the full sum. Grid slots in order: neighbouring
// invocations read the same cells. With uNearMasks, also the culling's near shell (above).
uniform float uRadiusScale, uCrossingScale, uLevel, uInteriorLevel;
uniform int uDropletAtoms, uFallbackNormals, uNearMasks;
void main() {
    uint slot = invocation();
    if (slot >= uCount) return;
    uint i = entryIndex(slot);
    vec3 x = entryPosition(slot).xyz;
    float h = particleH(i);
    const float PI = 3.14159265358979;
    float ownBound = attribute1(ATTR_VOLUME, i) / (PI * h * h * h) * (1.0 + 1e-4);
    float reach2 = 4.0 * h * h, field = 0.0;
    int neighbours = uDropletAtoms > 0 ? -1 : 0;  // itself
    int level = levelOf(h);
    Level g = levels[level];
    ivec3 home = ivec3(floor((x - g.originCell.xyz) * levelInvCell(g)));
    // Every kernel of the level taken at the level's least W(0): no read of each kernel's own,
    // and still a lower bound (INTERIOR at 1M particles about -13 ms). Where the volumes of a
    // level vary, it settles fewer particles and leaves more to the exact path; in every
    // default scene and the real sequences it settles the same ones as before.
    float coefficientMin = uintBitsToFloat(levelCoefficientMin[level]);
    float maxRadius = uRadiusScale * h, cap = min(maxRadius, uCrossingScale * maxRadius);
    float nearLimit2 = uNearMasks != 0 ? NEAR_SHELL * NEAR_SHELL * cap * cap : -1.0;
    float innerLimit2 = INNER_SHELL * INNER_SHELL * cap * cap;
    uvec4 inner = uvec4(0u), outer = uvec4(0u);
    uint visit = 0u;
#define ADD_CENTRE(k)                                                                \
    {                                                                                \
        vec4 e = entryPosition(k);                                                   \
        vec3 d = e.xyz - x;                                                          \
        field += coefficientMin * m4Shape(length(d) * e.w);                          \
        float dist2 = dot(d, d);                                                     \
        if (dist2 < reach2) ++neighbours;                                            \
        if (dist2 <= nearLimit2 && visit < NEAR_MASK_BITS && k != slot) {            \
            if (dist2 <= innerLimit2)                                                \
                inner[visit >> 5] |= 1u << (visit & 31u);                            \
            else                                                                     \
                outer[visit >> 5] |= 1u << (visit & 31u);                            \
        }                                                                            \
        ++visit;                                                                     \
    }
    FOR_EACH_IN_BLOCK(g, (home - ivec3(1)), 3, ADD_CENTRE)
#undef ADD_CENTRE
    if (uNearMasks != 0) {
        nearMasks[2u * slot] = inner;
        nearMasks[2u * slot + 1u] = outer;
    }
    if (!(field >= uInteriorLevel && field > max(uLevel, ownBound) &&
          neighbours >= uDropletAtoms)) {
        appendWalk(i);
        return;
    }
    radii[i] = cap;
    flags[i] |= INTERIOR_BIT;
    if (uFallbackNormals != 0) writeNormal(i, fallbackNormal(i, x));
}
#endif

#ifdef INTERIOR_DRAWN
// The particles INTERIOR settled that may be drawn (a surface, not hidden where culled, not a
// droplet's), listed for NORMALS.
uniform int uCull;
void main() {
    uint i = invocation();
    if (i >= uCount) return;
    uint f = flags[i];
    if ((f & INTERIOR_BIT) != 0u && radii[i] > 0.0 && !(uCull != 0 && (f & HIDDEN) != 0u) &&
        dropletSlot(i) == 0u)
        appendWalk(i);
}
#endif

#if defined(CULL_SPHERES) || defined(CULL) || defined(CULL_FULL)
// Per grid slot (the order of the grid's entries): the sphere the culling tests, its position
// and radius, the radius 0 where the particle neither hides nor is hidden (no radius, or a
// droplet's: renderer.cpp's cullRadii). One compact record per neighbour read: CULL_SPHERES
// writes them, the tests read them as a buffer texture (as the grid's entries).
#ifdef CULL_SPHERES
layout(std430, binding = 17) writeonly buffer CullSpheres {
    vec4 cullSpheres[];
};
#else
layout(binding = 10) uniform samplerBuffer uCullSphereTexels;
vec4 cullSphere(uint k) { return texelFetch(uCullSphereTexels, int(k)); }
#endif
#endif

#ifdef CULL_SPHERES
void main() {
    uint k = invocation();
    if (k >= uCount) return;
    uint i = entryIndex(k);
    float r = radii[i];
    cullSpheres[k] = vec4(entryPosition(k).xyz, r > 0.0 && dropletSlot(i) == 0u ? r : 0.0);
}
#endif

#if defined(CULL) || defined(CULL_FULL)
// occlusion_culling.cpp's exact test: hidden when every direction of the 162-point grid is
// covered, with the grid's covering margin, by the cap of an overlapping sphere of the same
// body, or when the sphere lies inside another (of equal coincident spheres the lower index
// stays). The caps of the nearest neighbours (within 1.4 radii, the widest) are tried first.
// Caps beyond MAX_CAPS are left out, which can only keep a sphere. The answer does not depend
// on the neighbours' order.
//
// CULL: one invocation per grid slot (neighbouring invocations test neighbouring spheres,
// which read the same cells and mostly take the same branches). Most spheres lie inside a
// body, buried under the wide caps of their nearest neighbours: a cheaper test first, the near
// shell alone (a third of the neighbourhood's volume) on the coarse grid's 42 directions with
// its wider margin, a sufficient condition of its own (a sphere it hides is hidden: exact as
// well, though it may hide a few borderline spheres the fine grid keeps). The near shell's
// slots come from INTERIOR's bits (nearMasks, with the field radii) or a walk that lists them
// by distance alone (one record read per neighbour, a cheap loop that every lane runs alike);
// then their caps (the body compared), each marking the coarse directions it covers in a bit
// mask (straight code over constants). The spheres it leaves are appended to a list that
// CULL_FULL takes (one dispatch over them alone, as RADIUS_WALK).
layout(binding = 11) uniform samplerBuffer uDirectionTexels;  // 162 unit directions, the
                                                             // coarse grid's 42 first
uniform float uCosMargin, uSinMargin, uRadiusScale;
uniform float uCoarseCosMargin, uCoarseSinMargin;
const int DIRECTIONS = 162, MAX_CAPS = 96;
float cullReach_ri;
float cullReach(float hMax) { return cullReach_ri + uRadiusScale * hMax; }
float probeReach(float hMax) { return uRadiusScale * hMax; }
void main() {
#if defined(CULL_FULL) && defined(CULL_PROBE)
    // The probe (below) over the walk list; the spheres it leaves are appended to the next list.
    if (invocation() >= walkDispatch.w) return;
    uint slot = walkList[invocation()];
#elif defined(CULL_FULL)
    // The full test over the next list.
    if (invocation() >= nextWalkDispatch.w) return;
    uint slot = walkList[uCount + invocation()];
#else
    uint slot = invocation();
    if (slot >= uCount) return;
#endif
    vec4 self = cullSphere(slot);
    float ri = self.w;
    if (!(ri > 0.0)) return;
    uint i = entryIndex(slot);
    vec3 xi = self.xyz;
    uint body = entryBody(slot);
    bool hidden = false;
    cullReach_ri = ri;
    float nearLimit2 = NEAR_SHELL * NEAR_SHELL * ri * ri;
    // The sphere in slot k if it overlaps (of the same body, neither hiding nor hidden
    // excluded): hidden where i lies inside it, else its cap of directions covered with margin
    // (COS_MARGIN, SIN_MARGIN) as CAP (unit axis, the least cosine of a covered direction);
    // NEAR_ONLY: the near shell only.
#define OVERLAP(k, COS_MARGIN, SIN_MARGIN, NEAR_ONLY, CAP)                                      \
    vec4 s_ = cullSphere(k);                                                                    \
    float rj_ = s_.w;                                                                           \
    vec3 d_ = s_.xyz - xi;                                                                      \
    float dist2_ = dot(d_, d_);                                                                 \
    float reach_ = ri + rj_;                                                                    \
    if (k != slot && rj_ > 0.0 && dist2_ < reach_ * reach_ && (!NEAR_ONLY || dist2_ <= nearLimit2) && \
        entryBody(k) == body) {                                                                 \
        float dist_ = sqrt(dist2_);                                                             \
        if (rj_ >= ri && dist_ + ri <= rj_) {                                                   \
            if (dist2_ > 0.0 || rj_ > ri || entryIndex(k) < i) hidden = true;                   \
        } else if (dist2_ > 0.0) {                                                              \
            float cosG = clamp((dist2_ + ri * ri - rj_ * rj_) / (2.0 * dist_ * ri), -1.0, 1.0); \
            if (cosG < COS_MARGIN) {                                                            \
                float sinG = sqrt(1.0 - cosG * cosG);                                           \
                vec4 CAP = vec4(d_ / dist_, cosG * COS_MARGIN + sinG * SIN_MARGIN + 2e-4);
#define END_OVERLAP \
    }               \
    }               \
    }
#ifndef CULL_FULL
    // The near shell's caps from the 3 x 3 x 3 cells of the particle's own level around its
    // cell (cells are at least the level's largest h: they hold the nearest neighbours), each
    // row of 3 cells one run of slots.
    const int COARSE_DIRECTIONS = 42, MAX_NEAR_CAPS = 32;
    // The coarse grid's directions, compiled in (per_set_gpu.cpp): the loops over them unroll
    // into straight code with constant operands.
    const vec3 COARSE[COARSE_DIRECTIONS] = vec3[](COARSE_DIRECTION_VALUES);
    // Each cap of the near shell marks the coarse directions it covers.
    uvec2 mask = uvec2(0u);  // bit d: coarse direction d covered (x), its opposite d + 21 (y)
    const uvec2 COVERED = uvec2((1u << uint(COARSE_DIRECTIONS / 2)) - 1u);
#define MARK_CAP(k)                                                             \
    {                                                                           \
        OVERLAP(k, uCoarseCosMargin, uCoarseSinMargin, true, cap)               \
        for (int d = 0; d < COARSE_DIRECTIONS / 2; ++d) {                       \
            float c = dot(COARSE[d], cap.xyz);                                  \
            if (c >= cap.w) mask.x |= 1u << uint(d);                            \
            if (-c >= cap.w) mask.y |= 1u << uint(d);                           \
        }                                                                       \
        END_OVERLAP                                                             \
    }
    Level g = levels[levelOf(particleH(i))];
    ivec3 base = ivec3(floor((xi - g.originCell.xyz) * levelInvCell(g))) - ivec3(1);
#ifdef NEAR_MASKS
    {
        // INTERIOR's bits: the t-th entry visited lies in the last row (blockRow's, as
        // FOR_EACH_IN_BLOCK visits them) whose first entry is visited at or before t. The
        // table's indices are constants once its loops unroll.
        uint rowStart[9], rowVisit[9];
        uint visits = 0u;
        for (int r = 0; r < 9; ++r) {
            uvec2 row = blockRow(g, base, 3, r);
            rowStart[r] = row.x;
            rowVisit[r] = visits;
            visits += row.y - row.x;
        }
        // The inner shell, then the outer where a direction is left.
        for (uint shell = 0u; shell < 2u && !hidden && mask != COVERED; ++shell) {
            uvec4 bits = nearMasks[2u * slot + shell];
            while (!hidden && any(notEqual(bits, uvec4(0u)))) {
                int w = bits.x != 0u ? 0 : bits.y != 0u ? 1 : bits.z != 0u ? 2 : 3;
                uint word = bits[w];
                bits[w] = word & (word - 1u);
                uint t = uint(32 * w + findLSB(word)), k = 0u;
                for (int r = 0; r < 9; ++r)
                    if (t >= rowVisit[r]) k = rowStart[r] + (t - rowVisit[r]);
                MARK_CAP(k)
            }
        }
    }
#else
    {
        // The near shell listed first, by distance alone (one record read per neighbour, a
        // cheap loop that every lane runs alike).
        uint near[MAX_NEAR_CAPS];  // grid slots (of any body: OVERLAP tests it)
        int nearCount = 0;
#define LIST_NEAR(k)                                                                       \
    {                                                                                      \
        vec4 s = cullSphere(k);                                                            \
        vec3 d = s.xyz - xi;                                                               \
        float dist2 = dot(d, d), reach = ri + s.w;                                         \
        if (k != slot && s.w > 0.0 && dist2 < reach * reach && dist2 <= nearLimit2 &&      \
            nearCount < MAX_NEAR_CAPS)                                                     \
            near[nearCount++] = k;                                                         \
    }
        FOR_EACH_IN_BLOCK(g, base, 3, LIST_NEAR)
#undef LIST_NEAR
        for (int n = 0; n < nearCount && !hidden; ++n) {
            uint k = near[n];
            MARK_CAP(k)
        }
    }
#endif
#undef MARK_CAP
    if (mask == COVERED) hidden = true;
    if (hidden) {
        flags[i] |= HIDDEN;
        return;
    }
    appendWalk(slot);  // left to CULL_FULL
#else
    // Most spheres the coarse test leaves are seen (at a surface). A probe first: the coarse
    // grid direction u nearest the particle's normal (one of the full grid's, outward at a
    // surface), tested against the caps of the overlapping spheres in one walk without lists.
    // Where no cap covers it and no sphere holds this one, the full test below could only find
    // that direction uncovered: the sphere is seen. A cap that covers u, or a sphere that holds
    // this one, holds the point p = x_i + r_i u, so the walk takes the ball of the largest
    // radius (radius_scale h) about p alone, not every overlapping sphere (at 1M particles
    // 27 -> 11 ms).
#ifdef CULL_PROBE
    {
        const vec3 COARSE[42] = vec3[](COARSE_DIRECTION_VALUES);
        vec3 normal = attribute3(ATTR_NORMAL, i), probe = COARSE[0];
        float best = dot(probe, normal);
        for (int d = 1; d < 42; ++d) {
            float c = dot(COARSE[d], normal);
            if (c > best) {
                best = c;
                probe = COARSE[d];
            }
        }
        bool covered = false;
#define PROBE(k)                                                  \
    {                                                             \
        OVERLAP(k, uCosMargin, uSinMargin, false, cap)            \
        covered = covered || dot(probe, cap.xyz) >= cap.w;        \
        END_OVERLAP                                               \
    }
        vec3 point = xi + ri * probe;
        FOR_EACH_NEAR(point, probeReach, PROBE)
#undef PROBE
        if (!covered && !hidden) {
            flags[i] = flags[i] & ~HIDDEN;
            return;
        }
        appendNextWalk(slot);  // the full test decides
    }
#else
    // The full test: every overlapping sphere, the near shell's caps first in the list. The
    // overlapping slots are listed first (a cheap loop), then their caps are made (the
    // arithmetic once per overlapping sphere, not once per neighbour visited).
    const int MAX_OVERLAPS = 160;
    uint overlaps[MAX_OVERLAPS];
    int overlapCount = 0;
#define LIST(k)                                                                       \
    {                                                                                 \
        vec4 s = cullSphere(k);                                                       \
        vec3 d = s.xyz - xi;                                                          \
        float reach = ri + s.w;                                                       \
        if (k != slot && s.w > 0.0 && dot(d, d) < reach * reach &&                    \
            overlapCount < MAX_OVERLAPS)                                              \
            overlaps[overlapCount++] = k;                                             \
    }
    FOR_EACH_NEAR(xi, cullReach, LIST)
#undef LIST
    vec4 caps[MAX_CAPS];
    int nearCaps = 0, farCaps = 0;
    for (int n = 0; n < overlapCount && !hidden; ++n) {
        uint k = overlaps[n];
        OVERLAP(k, uCosMargin, uSinMargin, false, cap)
        if (nearCaps + farCaps < MAX_CAPS) {
            if (dist2_ <= nearLimit2)
                caps[nearCaps++] = cap;
            else
                caps[MAX_CAPS - 1 - farCaps++] = cap;
        }
        END_OVERLAP
    }
    if (!hidden && nearCaps + farCaps > 0) {
        hidden = true;
        for (int dir = 0; dir < DIRECTIONS && hidden; ++dir) {
            vec3 u = texelFetch(uDirectionTexels, dir).xyz;
            bool covered = false;
            for (int c = 0; c < nearCaps && !covered; ++c) covered = dot(u, caps[c].xyz) >= caps[c].w;
            for (int c = MAX_CAPS - farCaps; c < MAX_CAPS && !covered; ++c)
                covered = dot(u, caps[c].xyz) >= caps[c].w;
            hidden = covered;
        }
    }
    flags[i] = (flags[i] & ~HIDDEN) | (hidden ? HIDDEN : 0u);
#endif  // CULL_PROBE
#endif
#undef OVERLAP
#undef END_OVERLAP
}
#endif

#ifdef NORMALS
// core::deriveNormals (derived_attributes.h): -grad c / |grad c| of the colour field at the
// particle, summed over every particle whose support covers it; where the sum cancels below
// (uFallbackRatio + FLT_EPSILON |x| / h) sum |dW/dr| (a lattice's interior), the radial
// direction from the particle's body centre, and the body's pole axis at the centre.
uniform float uFallbackRatio;
uniform int uFromList;  // the particles listed (INTERIOR's, INTERIOR_DRAWN's); else all
const float FLT_EPSILON = 1.1920929e-7;
void main() {
    // All: in grid order (the entries'), so that neighbouring invocations walk the same cells.
    uint i;
    vec3 x;
    if (uFromList != 0) {
        uint t = invocation();
        if (t >= walkDispatch.w) return;
        i = walkList[t];
        x = particlePosition(i);
    } else {
        uint slot = invocation();
        if (slot >= uCount) return;
        i = entryIndex(slot);
        x = entryPosition(slot).xyz;
    }
    vec3 gradient = vec3(0.0);
    float magnitudeSum = 0.0;
// Outside the support (q >= 2, where dW/dr is 0) and the particle itself are rejected on the
// squared distance, before the square root.
#define ADD_GRADIENT(k)                                                    \
    {                                                                      \
        vec4 e = entryPosition(k);                                         \
        vec3 d = x - e.xyz;                                                \
        float r2 = dot(d, d);                                              \
        if (r2 * (e.w * e.w) < 4.0 && r2 > 0.0) {                          \
            float r = sqrt(r2);                                            \
            float dWdr = entryCoefficients(k).x * m4ShapeDerivative(r * e.w); \
            gradient += (dWdr / r) * d;                                    \
            magnitudeSum -= dWdr;                                          \
        }                                                                  \
    }
    FOR_EACH_NEAR(x, supportReach, ADD_GRADIENT)
#undef ADD_GRADIENT
    float len = length(gradient);
    float resolvable = uFallbackRatio + FLT_EPSILON * length(x) / particleH(i);
    writeNormal(i, len > resolvable * magnitudeSum && len > 0.0 ? -gradient / len
                                                                : fallbackNormal(i, x));
}
#endif

#ifdef FIELD_NORMAL
// field_normal.cpp: the gradient and Hessian of the field at x_top = x_i + r_i n_i, as the
// first-order model of -grad c over the impostor, scaled by 1 / |grad c(x_top)|.
void main() {
    uint i = invocation();
    if (i >= uCount) return;
    float r = radii[i];
    vec3 normal = attribute3(ATTR_NORMAL, i);
    vec3 centre = particlePosition(i);
    vec3 offset = r * normal;
    vec3 point = centre + offset;
    vec3 gradient = vec3(0.0);
    mat3 hessian = mat3(0.0);
#define ADD_DERIVATIVES(k)                                                        \
    {                                                                             \
        vec4 e = entryPosition(k);                                                \
        vec3 delta = offset - (e.xyz - centre);                                   \
        float dist = length(delta);                                               \
        float q = dist * e.w;                                                     \
        if (q < 2.0 && dist > 0.0) {                                              \
            float coef = entryCoefficients(k).x;                                  \
            float dWdr = coef * m4ShapeDerivative(q);                             \
            float d2Wdr2 = coef * e.w * m4ShapeSecondDerivative(q);               \
            vec3 u = delta / dist;                                                \
            gradient += dWdr * u;                                                 \
            hessian += (d2Wdr2 - dWdr / dist) * outerProduct(u, u) + mat3(dWdr / dist); \
        }                                                                         \
    }
    FOR_EACH_NEAR(point, supportReach, ADD_DERIVATIVES)
#undef ADD_DERIVATIVES
    float length_ = length(gradient);
    if (!(length_ > 0.0)) {
        models[3u * i] = vec4(normal, 0.0);
        models[3u * i + 1u] = vec4(0.0);
        models[3u * i + 2u] = vec4(0.0);
        return;
    }
    mat3 m = -hessian / length_;
    models[3u * i] = vec4(-gradient / length_ - m * offset, 0.0);
    models[3u * i + 1u] = vec4(m[0][0], m[1][1], m[2][2], 0.0);
    models[3u * i + 2u] = vec4(m[0][1], m[0][2], m[1][2], 0.0);
}
#endif

#if defined(ANISOTROPY) || defined(DROPLET_FIT)
// core::symmetricEigen: the eigenvalues (descending) and unit eigenvectors (columns, a
// right-handed frame) of the symmetric C by cyclic Jacobi rotations, at most SWEEPS sweeps,
// done once the off-diagonal sum is below TINY or EPSILON times the diagonal's. For float
// (ANISOTROPY) and double (DROPLET_FIT, the CPU's precision).
#define SYMMETRIC_EIGEN(T, VEC3, MAT3, SWEEPS, TINY, EPSILON)                                 \
    void symmetricEigen(MAT3 c, out VEC3 values, out MAT3 vectors) {                          \
        T a[3][3]; /* a[row][col] as c[col][row]; v accumulates the rotations */              \
        T v[3][3];                                                                            \
        for (int row = 0; row < 3; ++row)                                                     \
            for (int col = 0; col < 3; ++col) {                                               \
                a[row][col] = row <= col ? c[col][row] : c[row][col];                         \
                v[row][col] = row == col ? T(1) : T(0);                                       \
            }                                                                                 \
        const ivec2 PAIRS[3] = ivec2[](ivec2(0, 1), ivec2(0, 2), ivec2(1, 2));                \
        for (int sweep = 0; sweep < SWEEPS; ++sweep) {                                        \
            T off = abs(a[0][1]) + abs(a[0][2]) + abs(a[1][2]);                               \
            T scale = abs(a[0][0]) + abs(a[1][1]) + abs(a[2][2]);                             \
            if (!(off > TINY) || off <= EPSILON * scale) break;                               \
            for (int pq = 0; pq < 3; ++pq) {                                                  \
                int p = PAIRS[pq].x, q = PAIRS[pq].y;                                         \
                if (a[p][q] == T(0)) continue;                                                \
                T theta = (a[q][q] - a[p][p]) / (T(2) * a[p][q]);                             \
                T t = (theta >= T(0) ? T(1) : T(-1)) / (abs(theta) + sqrt(theta * theta + T(1))); \
                T cs = T(1) / sqrt(t * t + T(1)), sn = t * cs;                                \
                for (int k = 0; k < 3; ++k) {                                                 \
                    T akp = a[k][p], akq = a[k][q];                                           \
                    a[k][p] = cs * akp - sn * akq;                                            \
                    a[k][q] = sn * akp + cs * akq;                                            \
                }                                                                             \
                for (int k = 0; k < 3; ++k) {                                                 \
                    T apk = a[p][k], aqk = a[q][k];                                           \
                    a[p][k] = cs * apk - sn * aqk;                                            \
                    a[q][k] = sn * apk + cs * aqk;                                            \
                }                                                                             \
                a[p][q] = T(0);                                                               \
                a[q][p] = T(0);                                                               \
                for (int k = 0; k < 3; ++k) {                                                 \
                    T vkp = v[k][p], vkq = v[k][q];                                           \
                    v[k][p] = cs * vkp - sn * vkq;                                            \
                    v[k][q] = sn * vkp + cs * vkq;                                            \
                }                                                                             \
            }                                                                                 \
        }                                                                                     \
        /* Descending, stable (std::stable_sort's order for equal values). */                 \
        ivec3 order = ivec3(0, 1, 2);                                                         \
        if (a[order.y][order.y] > a[order.x][order.x]) order.xy = order.yx;                   \
        if (a[order.z][order.z] > a[order.y][order.y]) order.yz = order.zy;                   \
        if (a[order.y][order.y] > a[order.x][order.x]) order.xy = order.yx;                   \
        for (int k = 0; k < 3; ++k) {                                                         \
            values[k] = a[order[k]][order[k]];                                                \
            vectors[k] = VEC3(v[0][order[k]], v[1][order[k]], v[2][order[k]]);                \
        }                                                                                     \
        if (dot(cross(vectors[0], vectors[1]), vectors[2]) < T(0)) vectors[2] = -vectors[2];  \
    }
#endif
#ifdef ANISOTROPY
SYMMETRIC_EIGEN(float, vec3, mat3, 16, 1e-30, 1e-9)
#endif
#ifdef DROPLET_FIT
SYMMETRIC_EIGEN(double, dvec3, dmat3, 32, 1e-300LF, 1e-17LF)
#endif

#ifdef ANISOTROPY
// anisotropy.cpp (Yu & Turk 2013): the weighted covariance of the neighbours within 2 h, its
// eigen-decomposition (core::symmetricEigen's cyclic Jacobi rotations), the clamped spread
// scaled to the impostor sphere's volume, the smoothed and anchored centre. Offsets are in
// units of h (the covariance of order 1 at any scale).
uniform float uSmoothing, uMaxAxisRatio;
uniform int uMinNeighbours, uAnchorSurface;
float ballReach_h;
float ballReach(float hMax) { return ballReach_h; }

void writeSphere(uint i, float r) {
    models[3u * i] = vec4(r, 0.0, 0.0, 0.0);
    models[3u * i + 1u] = vec4(0.0, r, 0.0, 0.0);
    models[3u * i + 2u] = vec4(0.0, 0.0, r, 0.0);
}

void main() {
    uint i = invocation();
    if (i >= uCount) return;
    float r = radii[i];
    if (!(r > 0.0)) {
        writeSphere(i, r);
        return;
    }
    float h = particleH(i);
    vec3 centre = particlePosition(i);
    float radius = 2.0 * h;
    ballReach_h = radius;
    float inverse = 1.0 / radius;
    float weight = 0.0;
    vec3 first = vec3(0.0);
    mat3 second = mat3(0.0);
    int neighbours = 0;
#define GATHER_MOMENTS(k)                                                  \
    {                                                                      \
        vec3 d = entryPosition(k).xyz - centre;                            \
        float q = length(d) * inverse;                                     \
        if (q < 1.0) {                                                     \
            float w = 1.0 - q * q * q;                                     \
            vec3 s = d / h;                                                \
            weight += w;                                                   \
            first += w * s;                                                \
            second += w * outerProduct(s, s);                              \
            neighbours += entryIndex(k) != i ? 1 : 0; \
        }                                                                  \
    }
    FOR_EACH_NEAR(centre, ballReach, GATHER_MOMENTS)
#undef GATHER_MOMENTS
    if (neighbours < uMinNeighbours || !(weight > 0.0)) {
        writeSphere(i, r);
        return;
    }
    vec3 mean = first / weight;
    mat3 c = second / weight - outerProduct(mean, mean);
    vec3 values;
    mat3 vectors;
    symmetricEigen(c, values, vectors);
    float largest = values[0];
    if (!(largest > 0.0)) {
        writeSphere(i, r);
        return;
    }
    vec3 spread = max(values, vec3(largest / uMaxAxisRatio));
    float scale = r / pow(spread.x * spread.y * spread.z, 1.0 / 3.0);
    mat3 axes = mat3(scale * spread[0] * vectors[0], scale * spread[1] * vectors[1],
                     scale * spread[2] * vectors[2]);
    vec3 shift = uSmoothing * mean * h;
    vec3 normal = attribute3(ATTR_NORMAL, i);
    if (uAnchorSurface != 0 && length(normal) > 0.0) {
        vec3 n = normalize(normal);
        float reach = dot(shift, n) + length(n * axes);
        shift += (r - reach) * n;
    }
    for (int k = 0; k < 3; ++k) models[3u * i + uint(k)] = vec4(axes[k], shift[k]);
}
#endif

// ---- The small droplets (droplets.h) ----
// RADIUS_WALK lists the sparse particles (a surface, fewer than droplet_atoms neighbours within
// 2 h). DROPLET_EDGES joins each to the sparse neighbours within its 2 h whose midpoint with it
// lies inside the level set (union-find: a root is hooked under the smaller one by compare-and-
// swap, so each cluster's root is its least index whatever the order), and marks it JOINS_BIT
// where such a neighbour is not sparse (the cluster is part of a body). DROPLET_CLUSTERS counts
// each cluster's members at its root, DROPLET_LINKS lists the members of the clusters of
// 2 .. droplet_atoms without JOINS_BIT at their root, and DROPLET_FIT fits each one's ellipsoid
// at its root (its first particle), as fitDroplets does on the CPU, sums in the same order
// (float field sums, as the radii's). Nothing is read back.
#if defined(DROPLET_EDGES) || defined(DROPLET_FIT)
uniform float uLevel;
// The colour field at P (every kernel that reaches it, in the grid's order).
float fieldAt(vec3 p) {
    float value = 0.0;
#define ADD_FIELD(k)                                                                \
    {                                                                               \
        vec4 e = entryPosition(k);                                                  \
        value += entryCoefficients(k).x / e.w * m4Shape(length(e.xyz - p) * e.w);   \
    }
    FOR_EACH_NEAR(p, supportReach, ADD_FIELD)
#undef ADD_FIELD
    return value;
}
#endif
#if defined(DROPLET_EDGES) || defined(DROPLET_CLUSTERS)
uint findRoot(uint x) {
    for (uint p = PARENT(x); p != x; p = PARENT(x)) x = p;
    return x;
}
#endif
const uint CLUSTER_JOINS = 0x80000000u;  // CLUSTER(root): a member has JOINS_BIT

#ifdef DROPLET_EDGES
void unite(uint a, uint b) {
    for (;;) {
        a = findRoot(a);
        b = findRoot(b);
        if (a == b) return;
        if (a > b) {
            uint t = a;
            a = b;
            b = t;
        }
        if (atomicCompSwap(PARENT(b), b, a) == b) return;  // else b was hooked meanwhile
    }
}
float edgeReach_;
float edgeReach(float hMax) { return edgeReach_; }
void main() {
    uint i = sparseParticle();
    if (i == NO_MEMBER) return;
    vec3 x = particlePosition(i);
    float reach = 2.0 * particleH(i);  // core::M4_SUPPORT h
    edgeReach_ = reach;
    bool joins = false;
#define EDGE(k)                                                                               \
    {                                                                                         \
        vec4 e = entryPosition(k);                                                            \
        vec3 d = e.xyz - x;                                                                   \
        uint j = entryIndex(k);                                     \
        if (j != i && dot(d, d) < reach * reach && fieldAt(0.5 * (x + e.xyz)) > uLevel) {     \
            if ((flags[j] & SPARSE_BIT) == 0u)                                                \
                joins = true;                                                                 \
            else                                                                              \
                unite(i, j);                                                                  \
        }                                                                                     \
    }
    FOR_EACH_NEAR(x, edgeReach, EDGE)
#undef EDGE
    if (joins) flags[i] |= JOINS_BIT;
}
#endif

#ifdef DROPLET_CLUSTERS
void main() {
    uint i = sparseParticle();
    if (i == NO_MEMBER) return;
    uint root = findRoot(i);
    PARENT(i) = root;  // path compression: the root is an ancestor whatever others write
    atomicAdd(CLUSTER(root), 1u);
    if ((flags[i] & JOINS_BIT) != 0u) atomicOr(CLUSTER(root), CLUSTER_JOINS);
}
#endif

#ifdef DROPLET_LINKS
uniform int uDropletAtoms;
void main() {
    uint i = sparseParticle();
    if (i == NO_MEMBER) return;
    uint root = PARENT(i);
    uint cluster = CLUSTER(root), size = cluster & ~CLUSTER_JOINS;
    if ((cluster & CLUSTER_JOINS) != 0u || size < 2u || size > uint(uDropletAtoms)) return;
    PARENT(i) = atomicExchange(MEMBERS(root), i);  // the next member
}
#endif

#ifdef DROPLET_FIT
layout(std430, binding = 16) writeonly buffer Droplets {
    vec4 droplets[];  // the ellipsoids, then the normal models (dropletSlot above)
};
const int MAX_DROPLET_ATOMS = 64;  // settings.cpp's limit of droplet_atoms
// impostor_radius.cpp's fieldCrossing: the distance from CENTRE along DIRECTION to the level
// set, 0 where the field at the centre is not above it, MAX_RADIUS where it is above at the
// early-exit samples or at every scan sample.
// centreAbove: whether the field at the centre is above the level (the same for every
// direction: the caller finds it once).
bool above(dvec3 p) { return fieldAt(vec3(p)) > uLevel; }
double fieldCrossing(dvec3 centre, bool centreAbove, dvec3 direction, double maxRadius) {
    const int SCAN_STEPS = 8, BISECTION_STEPS = 10;
    if (!centreAbove) return 0.0LF;
    if (above(centre + maxRadius * direction) && above(centre + 0.5LF * maxRadius * direction))
        return maxRadius;
    double inside = 0.0LF, outside = -1.0LF;
    for (int k = 1; k <= SCAN_STEPS && outside < 0.0LF; ++k) {
        double t = maxRadius * double(k) / double(SCAN_STEPS);
        if (above(centre + t * direction))
            inside = t;
        else
            outside = t;
    }
    if (outside < 0.0LF) return maxRadius;
    for (int k = 0; k < BISECTION_STEPS; ++k) {
        double t = 0.5LF * (inside + outside);
        if (above(centre + t * direction))
            inside = t;
        else
            outside = t;
    }
    return 0.5LF * (inside + outside);
}
void main() {
    uint first = sparseParticle();
    if (first == NO_MEMBER || MEMBERS(first) == NO_MEMBER) return;  // a droplet's root only
    uint members[MAX_DROPLET_ATOMS];
    int count = 0;
    for (uint m = MEMBERS(first); m != NO_MEMBER && count < MAX_DROPLET_ATOMS; m = PARENT(m))
        members[count++] = m;
    // Ascending, the CPU's order of the sums (insertion sort; Mesa 22.3's llvmpipe lost
    // members where the loop's condition compared them).
    for (int k = 1; k < count; ++k)
        for (int j = k; j > 0; --j) {
            uint lower = members[j - 1], upper = members[j];
            if (lower <= upper) break;
            members[j] = lower;
            members[j - 1] = upper;
        }
    dvec3 mean = dvec3(0.0LF);
    for (int k = 0; k < count; ++k) mean += dvec3(particlePosition(members[k]));
    mean /= double(count);
    dmat3 covariance = dmat3(0.0LF);
    double reach = 0.0LF;  // beyond it from the mean no member's kernel adds to the field
    for (int k = 0; k < count; ++k) {
        dvec3 d = dvec3(particlePosition(members[k])) - mean;
        covariance += outerProduct(d, d);
        reach = max(reach, length(d) + 2.0LF * double(particleH(members[k])));
    }
    dvec3 values;
    dmat3 vectors;
    symmetricEigen(covariance, values, vectors);
    dvec3 centre = mean;
    mat3 axes;
    bool meanAbove = above(mean);
    for (int k = 0; k < 3; ++k) {
        dvec3 e = vectors[k];
        double plus = fieldCrossing(mean, meanAbove, e, reach),
               minus = fieldCrossing(mean, meanAbove, -e, reach);
        // No surface about the mean, or none found within the cluster's reach: spheres.
        if (!(plus > 0.0LF && minus > 0.0LF) || plus >= reach || minus >= reach) return;
        centre += 0.5LF * (plus - minus) * e;
        axes[k] = vec3(0.5LF * (plus + minus) * e);
    }
    vec3 shift = vec3(centre - dvec3(particlePosition(first)));
    uint slot = atomicAdd(dropletCount, 1u);
    // droplets.cpp's dropletNormalModel: M = sum_k a_k a_k^T / |a_k|^4.
    mat3 model = mat3(0.0);
    for (int k = 0; k < 3; ++k) {
        float length2 = dot(axes[k], axes[k]);
        model += outerProduct(axes[k], axes[k]) / (length2 * length2);
        droplets[3u * slot + uint(k)] = vec4(axes[k], shift[k]);
    }
    uint m = dropletModel(slot);
    droplets[m] = vec4(-(model * shift), 0.0);
    droplets[m + 1u] = vec4(model[0][0], model[1][1], model[2][2], 0.0);
    droplets[m + 2u] = vec4(model[1][0], model[2][0], model[2][1], 0.0);
    for (int k = 0; k < count; ++k) radii[members[k]] = 0.0;
    // The radius of the sphere of the ellipsoid's volume (the culling and the near test).
    radii[first] = pow(length(axes[0]) * length(axes[1]) * length(axes[2]), 1.0 / 3.0);
    flags[first] |= (slot + 1u) << 8;
}
#endif

// ---- The frame's draw lists ----

#if defined(MARK) || defined(PACK) || defined(FINISH) || defined(KERNELS) || \
    defined(PACK_KERNELS)
layout(std430, binding = 14) buffer DrawLists {
    uint drawnPrefix[];  // n + 1: exclusive prefix of the drawn particles; then n + 1 of kernels
};
#endif

#if defined(NEAR) || defined(NEAR_BOUND)
// renderer.cpp's cullingIsExact: whether a drawn sphere reaches into the near plane's ball.
uniform dvec3 uCamera;
uniform double uNearReach;
#endif

#ifdef NEAR_BOUND
// Whether NEAR runs: only where the camera's ball, widened by a level's largest radius
// (radius_scale times its largest h: no radius is larger; droplets are not tested), reaches
// the level's box. A camera outside the particles' reach skips the pass over every particle
// (at 1M particles, 4 ms).
uniform float uRadiusScale;
void main() {
    if (invocation() != 0u) return;
    bool mayReach = false;
    for (uint u = 0u; u < usedLevels; ++u) {
        Level g = levels[levelList[u]];
        dvec3 lo = dvec3(levelLow(g)), hi = dvec3(levelHigh(g));
        dvec3 outside = max(max(lo - uCamera, uCamera - hi), dvec3(0.0));
        double radius = double(uRadiusScale) * double(uintBitsToFloat(g.maxKey.w));
        mayReach = mayReach || length(outside) - radius <= uNearReach;
    }
    nearDispatch = uvec4(mayReach ? (uCount + 63u) / 64u : 0u, 1u, 1u, 0u);
}
#endif

#ifdef NEAR
void main() {
    uint i = invocation();
    if (i >= uCount || !(radii[i] > 0.0) || dropletSlot(i) != 0u) return;
    if (length(dvec3(particlePosition(i)) - uCamera) - double(radii[i]) <= uNearReach)
        atomicOr(nearHit, 1u);
}
#endif

#ifdef MARK
// The drawn particles are also listed, for KERNELS and PACK; with uDropletsApart the droplets
// are listed but take no slot of the particles' draw (PACK puts them in a draw of their own).
uniform int uCull, uDropletsApart;
void main() {
    uint i = invocation();
    if (i >= uCount) return;
    bool hidden = uCull != 0 && nearHit == 0u && (flags[i] & HIDDEN) != 0u;
    bool drawn = radii[i] > 0.0 && !hidden;
    drawnPrefix[i] = drawn && !(uDropletsApart != 0 && dropletSlot(i) != 0u) ? 1u : 0u;
    drawnPrefix[uCount + 1u + i] = 0u;
    if (drawn) appendWalk(i);
}
#endif

#ifdef KERNELS
// The kernels the gradient pass adds: those whose support (2 h) reaches a drawn impostor, where
// every surface point of the G-buffer lies. Exact: a G-buffer pixel's gradient sums every kernel
// whose support covers it (surface_kernels.h's probes, on the CPU, leave out a few whose share
// is small). Each drawn particle marks its neighbours; the marks do not depend on the order.
// A kernel is marked by some fifty drawn particles on a body's surface: each reads the mark
// before writing it, since llvmpipe stores lane by lane at more cost than it loads (KERNELS at
// 1M particles 59 -> 49 ms).
uniform int uEllipsoids;
float kernelReach_r;
float kernelReach(float hMax) { return kernelReach_r + 2.0 * hMax; }
void main() {
    if (invocation() >= walkDispatch.w) return;
    uint i = walkList[invocation()];  // a drawn particle
    float r = radii[i];
    vec3 centre = particlePosition(i);
    uint slot = dropletSlot(i);
    if (slot != 0u || uEllipsoids != 0) {
        // The ellipsoid lies within |shift| + its longest semi-axis of the particle. Branches,
        // not ?: selects, which a compiler may evaluate on both sides (the droplets' index is
        // out of range for slot 0).
        vec4 a0, a1, a2;
        if (slot != 0u) {
            uint d = 3u * (slot - 1u);
            a0 = droplets[d];
            a1 = droplets[d + 1u];
            a2 = droplets[d + 2u];
        } else {
            a0 = models[3u * i];
            a1 = models[3u * i + 1u];
            a2 = models[3u * i + 2u];
        }
        r = length(vec3(a0.w, a1.w, a2.w)) +
            max(length(a0.xyz), max(length(a1.xyz), length(a2.xyz)));
    }
    kernelReach_r = r;
#define MARK_KERNEL(k)                                                   \
    {                                                                    \
        vec4 e = entryPosition(k);                                       \
        float reach = r + 2.0 / e.w;                                     \
        vec3 d = e.xyz - centre;                                         \
        uint mark = uCount + 1u + entryIndex(k); \
        if (dot(d, d) < reach * reach && drawnPrefix[mark] == 0u)          \
            drawnPrefix[mark] = 1u;                                        \
    }
    FOR_EACH_NEAR(centre, kernelReach, MARK_KERNEL)
#undef MARK_KERNEL
}
#endif

#if defined(PACK) || defined(PACK_KERNELS)
// gpu_scene.cpp's packParticles, packEllipsoids and packKernels: positions relative to the
// camera, subtracted in double. PACK takes the drawn particles MARK listed, PACK_KERNELS every
// particle, each writing its slot of the prefix sum (so the list's order does not matter).
// Two programs: one invocation of the whole of PACK costs llvmpipe more than one of
// PACK_KERNELS, whatever branch it takes (pack at 1M particles 36 -> 27 ms).
uniform dvec3 uCamera;
#endif

#ifdef PACK
struct Particle {
    vec4 positionRadius;
    vec4 normalU;
    vec4 dudxV;
    vec4 dvdxBody;
    vec4 glowMaterial;
    vec4 hessianDiagonal;
    vec4 hessianOffDiagonal;
};
layout(std430, binding = 0) writeonly buffer Particles {
    Particle particles[];
};
layout(std430, binding = 4) writeonly buffer Ellipsoids {
    vec4 ellipsoids[];
};
uniform int uModels;  // 0: none, 1: field normals, 2: ellipsoids (droplets' among them)
#endif
#if defined(PACK) || defined(FINISH)
// Spheres: the droplets (every one is drawn: they neither hide nor are hidden) in a draw of
// their own, first in the particles' buffer in the order of their slots (their ellipsoids are
// the Droplets buffer's first records, at the same index), the spheres after them.
uniform int uDropletsApart;
uint firstSphere() { return uDropletsApart != 0 ? dropletCount : 0u; }
#endif
#ifdef PACK
void main() {
    uint t = invocation();
    if (t >= walkDispatch.w) return;
    uint i = walkList[t];
    uint k = firstSphere() + drawnPrefix[i];
    vec2 uv =
        vec2(attributeFloat(ATTR_UV * uCount + 2u * i), attributeFloat(ATTR_UV * uCount + 2u * i + 1u));
    Particle p;
    p.positionRadius = vec4(vec3(dvec3(particlePosition(i)) - uCamera), radii[i]);
    p.normalU = vec4(attribute3(ATTR_NORMAL, i), uv.x);
    p.dudxV = vec4(attribute3(ATTR_DUDX, i), uv.y);
    p.dvdxBody = vec4(attribute3(ATTR_DVDX, i), float(attributeBits(ATTR_BODY, i)));
    p.glowMaterial = vec4(attribute3(ATTR_GLOW, i), float(attributeBits(ATTR_MATERIAL, i)));
    p.hessianDiagonal = vec4(0.0);
    p.hessianOffDiagonal = vec4(0.0);
    uint slot = dropletSlot(i);
    // Branches rather than ?: selects (KERNELS says why).
    if (uModels == 1 && slot != 0u) {
        // A droplet's normal is its ellipsoid's.
        uint m = dropletModel(slot - 1u);
        p.normalU.xyz = droplets[m].xyz;
        p.hessianDiagonal = droplets[m + 1u];
        p.hessianOffDiagonal = droplets[m + 2u];
    } else if (uModels == 1) {
        p.normalU.xyz = models[3u * i].xyz;
        p.hessianDiagonal = models[3u * i + 1u];
        p.hessianOffDiagonal = models[3u * i + 2u];
    }
    if (uDropletsApart != 0 && slot != 0u) {
        particles[slot - 1u] = p;
        return;
    }
    if (uModels == 2 && slot != 0u) {
        for (uint a = 0u; a < 3u; ++a) ellipsoids[3u * k + a] = droplets[3u * (slot - 1u) + a];
    } else if (uModels == 2) {
        for (uint a = 0u; a < 3u; ++a) ellipsoids[3u * k + a] = models[3u * i + a];
    }
    particles[k] = p;
}
#endif

#ifdef PACK_KERNELS
struct Kernel {
    vec4 positionSupport;
    vec4 coefficients;
};
layout(std430, binding = 3) writeonly buffer Kernels {
    Kernel kernels[];
};
void main() {
    uint i = invocation();
    if (i >= uCount) return;
    uint kernelBase = uCount + 1u;
    uint k = drawnPrefix[kernelBase + i];
    if (drawnPrefix[kernelBase + i + 1u] == k) return;
    double h = double(particleH(i));
    double v = double(attribute1(ATTR_VOLUME, i));
    const double PI = 3.14159265358979323846LF;
    kernels[k].positionSupport = vec4(vec3(dvec3(particlePosition(i)) - uCamera), float(2.0LF * h));
    kernels[k].coefficients = vec4(float(v / (PI * h * h * h * h)), float(1.0LF / h), 0.0, 0.0);
}
#endif

#ifdef FINISH
void main() {
    if (invocation() != 0u) return;
    drawParticles = uvec4(6u * drawnPrefix[uCount], 1u, 6u * firstSphere(), 0u);
    drawKernels = uvec4(6u * drawnPrefix[2u * uCount + 1u], 1u, 0u, 0u);
    drawDroplets = uvec4(6u * dropletCount, 1u, 0u, 0u);
}
#endif
