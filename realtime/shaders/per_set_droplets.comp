// The per-set stages of the small droplets (droplets.h), one per #define: DROPLET_EDGES,
// DROPLET_CLUSTERS, DROPLET_LINKS, DROPLET_FIT.
#ifdef DROPLET_FIT
#define DROPLETS_ACCESS writeonly  // the ellipsoids and normal models it fits
#endif
layout(local_size_x = 64) in;
#define USES_RADII
#define USES_FLAGS
#define USES_DROPLETS
#define USES_DROPLET_WORK
#include "per_set_stages.glsl"

#ifdef DROPLET_FIT
SYMMETRIC_EIGEN(double, dvec3, dmat3, 32, 1e-300LF, 1e-17LF)
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
