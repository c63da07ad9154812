// The per-set stages' shared declarations (per_set_grid.comp, per_set_radius.comp,
// per_set_cull.comp, per_set_models.comp, per_set_droplets.comp, per_set_pack.comp): every
// storage block more than one group of stages reads or writes, at the binding per_set_gpu.cpp
// binds it to, and the helpers over it. A stage file names the blocks its stages use
// (USES_RADII, USES_FLAGS, USES_DROPLETS, USES_MODELS, USES_WALKS, USES_DROPLET_WORK,
// USES_NEAR_MASKS) before it includes this one: a driver may count every block declared
// against GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS (Mesa does for some stages), used or not. A block
// one stage alone uses is declared in that stage.
#include "per_set.glsl"

uint invocation() { return gl_GlobalInvocationID.x; }

#ifdef USES_RADII
layout(std430, binding = 11) buffer Radii {
    float radii[];
};
#endif

// flags: bit 1: hidden (occlusion_culling.h); bit 2: settled by INTERIOR (its normal is not
// derived until it may be drawn); bit 3: sparse (droplets.h: a surface, fewer than
// droplet_atoms neighbours); bit 4: a sparse particle with an edge to one that is not.
const uint HIDDEN = 2u, INTERIOR_BIT = 4u, SPARSE_BIT = 8u, JOINS_BIT = 16u;
#ifdef USES_FLAGS
layout(std430, binding = 12) buffer Flags {
    uint flags[];  // CULL writes bit 1 of its own particle's flags only
};
#endif

// A droplet's first particle: its slot + 1 in the flags from bit 8 (0: not a droplet's), and
// per droplet its ellipsoid (GpuEllipsoid, 3 vec4 from 3 slot: the droplets' draw reads them
// there) and, after the ellipsoids of the most droplets a set may hold (one per two
// particles), its field normal model (FieldNormal, 3 vec4 from dropletModel(slot)).
#ifdef USES_FLAGS
uint dropletSlot(uint i) { return flags[i] >> 8; }
#endif
uint dropletModel(uint slot) { return 3u * (max(uCount / 2u, 1u) + slot); }
#ifdef USES_DROPLETS
#ifndef DROPLETS_ACCESS
#define DROPLETS_ACCESS readonly
#endif
layout(std430, binding = 16) DROPLETS_ACCESS buffer Droplets {
    vec4 droplets[];
};
#endif

// Three vec4 per particle: FieldNormal (outward, -H diagonal, -H off-diagonal) or the ellipsoid
// (GpuEllipsoid: axes in xyz, the centre's shift in w).
#ifdef USES_MODELS
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
        uint entry_ = atomicAdd(DISPATCH.entries, 1u);                  \
        if (entry_ % gl_WorkGroupSize.x == 0u) atomicAdd(DISPATCH.groups, 1u); \
        LIST[(AT) + entry_] = (VALUE);                                  \
    }
#ifdef USES_WALKS
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
#ifdef USES_DROPLET_WORK
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
    return invocation() < sparseDispatch.entries ? dropletWork[invocation()] : NO_MEMBER;
}
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
#ifdef USES_NEAR_MASKS
const float NEAR_SHELL = 1.4, INNER_SHELL = 1.1;  // caps
const uint NEAR_MASK_BITS = 128u;
layout(std430, binding = 21) buffer NearMasks {
    uvec4 nearMasks[];  // per slot the inner shell, then the outer: bit t % 32 of word t / 32
                        // for the t-th entry visited
};
#endif

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
