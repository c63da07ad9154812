// The per-set stages of the occlusion culling (occlusion_culling.h), one per #define:
// CULL_SPHERES (the spheres per grid slot), CULL (the coarse test; NEAR_MASKS: from INTERIOR's
// near shells), CULL_FULL (the full test; CULL_PROBE: its probe first).
layout(local_size_x = 64) in;
#define USES_RADII
#define USES_FLAGS
#define USES_WALKS
#define USES_NEAR_MASKS
#include "per_set_stages.glsl"

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
    if (invocation() >= walkDispatch.entries) return;
    uint slot = walkList[invocation()];
#elif defined(CULL_FULL)
    // The full test over the next list.
    if (invocation() >= nextWalkDispatch.entries) return;
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
    ivec3 base = saturateToInt(floor((xi - g.originCell.xyz) * levelInvCell(g))) - ivec3(1);
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
