// The per-set stages of the neighbour grid (per_set.glsl), one per #define: INIT, H_MIN,
// LEVELS, LAYOUT, COUNT, SCATTER, SORT, GATHER (per_set_gpu.cpp's buildGrid, with scan.comp
// between COUNT and SCATTER).
#if defined(LAYOUT) || defined(INIT)
layout(local_size_x = 32) in;
#else
layout(local_size_x = 64) in;
#endif
#include "per_set_stages.glsl"

layout(std430, binding = 7) buffer Cells {
    uint cellOffsets[];  // COUNT: counts; after the scan: offsets (totalCells + 1)
};
layout(std430, binding = 8) buffer CellOf {
    uint cellOf[];  // per particle: its cell; SCATTER: then the fill count per cell after n
};
layout(std430, binding = 10) buffer Sorted {
    uint sorted[];  // particle indices by cell
};

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
        levels[L].minX = levels[L].minY = levels[L].minZ = 0xFFFFFFFFu;
        levels[L].count = 0u;
        levels[L].maxX = levels[L].maxY = levels[L].maxZ = levels[L].hMaxBits = 0u;
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
    atomicMin(levels[L].minX, lo.x);
    atomicMin(levels[L].minY, lo.y);
    atomicMin(levels[L].minZ, lo.z);
    atomicAdd(levels[L].count, lo.w);
    atomicMax(levels[L].maxX, hi.x);
    atomicMax(levels[L].maxY, hi.y);
    atomicMax(levels[L].maxZ, hi.z);
    atomicMax(levels[L].hMaxBits, hi.w);
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
        if (g.count == 0u) {
            levels[L].dims = ivec4(1, 1, 1, first);
            continue;
        }
        levelList[used++] = uint(L);
        vec3 lo = levelLow(g), hi = levelHigh(g);
        vec3 extent = hi - lo;
        float maxCells = max(4.0 * float(g.count), 4096.0);
        float cell = uintBitsToFloat(g.hMaxBits);
        vec3 n;
        float total;
        for (int k = 0; k < 200; ++k) {
            n = floor(extent / cell) + 1.0;
            total = n.x * n.y * n.z;
            if (total <= maxCells) break;
            cell *= max(1.01, pow(total / maxCells, 1.0 / 3.0));
        }
        // A box that no cell size fitted (a NaN or infinite extent: no finite set has one) is
        // one cell, rather than dims no int holds.
        if (isNanBits(total) || total > maxCells) n = vec3(1.0);
        levels[L].originCell = vec4(lo, cell);
        ivec3 dims = ivec3(clampToInt(n.x, 1, 1 << 30), clampToInt(n.y, 1, 1 << 30),
                           clampToInt(n.z, 1, 1 << 30));
        levels[L].dims = ivec4(dims, first);
        first += dims.x * dims.y * dims.z;
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
    atomicAdd(cellOffsets[c], 1u);
}
#endif

#ifdef SCATTER
void main() {
    uint i = invocation();
    if (i >= uCount) return;
    uint c = cellOf[i];
    uint slot = atomicAdd(cellOf[uCount + c], 1u);
    sorted[cellOffsets[c] + slot] = i;
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
    uint begin = cellOffsets[c], end = cellOffsets[c + 1u];
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
