// The per-set stages of the impostors' radii, one per #define: INTERIOR (the particles deep
// inside a body, and the culling's near shells), RADIUS and RADIUS_WALK (the level set along
// the normal), INTERIOR_DRAWN (the settled particles that may be drawn, listed for NORMALS).
#ifdef INTERIOR
#define WRITES_ATTRIBUTES  // the fallback normals of the particles it settles
#endif
layout(local_size_x = 64) in;
#define USES_RADII
#define USES_FLAGS
#define USES_WALKS
#define USES_DROPLET_WORK
#define USES_NEAR_MASKS
#include "per_set_stages.glsl"

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
    if (t >= nextWalkDispatch.entries) return;
    uint i = walkList[uCount + t];  // left by RADIUS's early exit
#else
    // "fixed": every particle; "field": those INTERIOR left, its list.
    uint i;
    if (uFixed != 0) {
        i = invocation();
        if (i >= uCount) return;
    } else {
        uint t = invocation();
        if (t >= walkDispatch.entries) return;
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
        vec3 capCell = floor((centre + 0.5 * cap - g.originCell.xyz) * inv);
        ivec3 base = saturateToInt(capCell) - ivec3(1);
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
    ivec3 home = saturateToInt(floor((x - g.originCell.xyz) * levelInvCell(g)));
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
