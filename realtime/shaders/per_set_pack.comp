// The per-frame stages of the draw lists, one per #define: NEAR_BOUND and NEAR (whether a
// sphere reaches into the near plane's ball), MARK (the drawn particles), PACK (their records),
// FINISH (the draw commands), REPLACED (the drawn particles of the bodies drawn as one sphere).
#if defined(FINISH)
layout(local_size_x = 32) in;
#else
layout(local_size_x = 64) in;
#endif
#define USES_RADII
#define USES_FLAGS
#define USES_DROPLETS
#define USES_MODELS
#define USES_WALKS
#include "per_set_stages.glsl"

// ---- The frame's draw lists ----

#if defined(MARK) || defined(PACK) || defined(FINISH)
layout(std430, binding = 14) buffer DrawLists {
    uint drawnPrefix[];  // n + 1: exclusive prefix of the drawn particles
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
        double radius = double(uRadiusScale) * double(uintBitsToFloat(g.hMaxBits));
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
// The drawn particles are also listed, for PACK; with uDropletsApart the droplets
// are listed but take no slot of the particles' draw (PACK puts them in a draw of their own).
uniform int uCull, uDropletsApart;
void main() {
    uint i = invocation();
    if (i >= uCount) return;
    bool hidden = uCull != 0 && nearHit == 0u && (flags[i] & HIDDEN) != 0u;
    bool drawn = radii[i] > 0.0 && !hidden;
    drawnPrefix[i] = drawn && !(uDropletsApart != 0 && dropletSlot(i) != 0u) ? 1u : 0u;
    if (drawn) appendWalk(i);
}
#endif

#ifdef PACK
// gpu_scene.cpp's packParticles and packEllipsoids: positions relative to the camera,
// subtracted in double. PACK takes the drawn particles MARK listed, each writing its slot of
// the prefix sum (so the list's order does not matter).
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
    if (t >= walkDispatch.entries) return;
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
    // Branches rather than ?: selects, which a compiler may evaluate on both sides (the
    // droplets' index is out of range for slot 0).
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


#ifdef FINISH
void main() {
    if (invocation() != 0u) return;
    drawParticles = uvec4(6u * drawnPrefix[uCount], 1u, 6u * firstSphere(), 0u);
    drawDroplets = uvec4(6u * dropletCount, 1u, 0u, 0u);
}
#endif

#ifdef REPLACED
// realtime.particles.body_sphere_pixels (per_set.cpp): of the drawn particles MARK listed, those
// whose body is drawn as one sphere this frame (the impostor programs' BODY_MASK drops them),
// and the droplets among them, counted for the frame's particles_drawn and droplets, which
// leave them out as the CPU path's packing does. Only in frames that replace a body; one atomic
// per such particle.
#define BODY_MASK_ACCESS
#include "body_mask.glsl"
void main() {
    uint t = invocation();
    if (t >= walkDispatch.entries) return;
    uint i = walkList[t];
    if (!bodyReplaced(attributeBits(ATTR_BODY, i))) return;
    atomicAdd(replacedDrawn, 1u);
    if (dropletSlot(i) != 0u) atomicAdd(replacedDroplets, 1u);
}
#endif
