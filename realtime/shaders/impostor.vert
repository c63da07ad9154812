// One camera-facing quad per particle (six vertices, gl_VertexID / 6 = the particle), sized
// so that it covers the impostor's silhouette; the fragment shader intersects the impostor.
//
// Camera pass: the quad lies in the plane through the impostor's centre perpendicular to the
// direction eye -> centre. A sphere's silhouette cone (half-angle asin(r / D)) cuts that
// plane in a circle of radius r D / sqrt(D^2 - r^2), which the quad circumscribes.
// ELLIPSOID: the quad is the bounding rectangle, in the same plane, of the ellipsoid's
// silhouette (Sigg et al. 2006, "GPU-Based Ray-Casting of Quadratic Surfaces": the roots of
// the quadric's projection), written with every length divided by D so that no square of a
// large distance appears.
// BODY_SPHERE: the records are whole bodies' spheres (packBodySpheres), drawn as spheres; only
// the fragment shader reads them otherwise.
// BODY_MASK (per_set = "gpu" in a frame that draws some body as its sphere, body_mask.glsl):
// the GPU packs every particle, so a particle of a replaced body is dropped here.
// SHADOW_PASS: orthographic from the light; the quad is perpendicular to the light, half-size r
// (ELLIPSOID: the ellipsoid's half-extents along the light's x and y).
#include "common.glsl"
#include "convert.glsl"
#include "particles.glsl"
#ifndef SHADOW_PASS
#include "textures.glsl"
#endif
#ifdef BODY_MASK
#include "body_mask.glsl"
#endif

out vec2 vOffset;           // position in the quad plane relative to the centre, scene units
#ifndef SHADOW_PASS
out vec3 vQuadPoint;        // eye-space position on the quad
flat out float vCentreDistance;  // D: distance eye -> centre
#else
flat out float vCentreDepth;     // light-space depth of the centre
#endif
#ifdef ELLIPSOID
flat out mat3 vInverseAxes;  // eye (light) space -> the ellipsoid's unit-sphere space: A^-1
#ifndef SHADOW_PASS
out vec3 vQuadOffset;        // eye-space position on the quad relative to the ellipsoid's centre
#endif
#endif
flat out float vRadius;
#ifndef SHADOW_PASS
// The particle's attributes, fetched once per vertex rather than once per fragment.
flat out vec3 vCentre;        // eye space; the particle's position (an ellipsoid's centre may differ)
flat out vec3 vNormal;        // world (field_normal.h: not unit)
flat out vec3 vHessianDiagonal;
flat out vec3 vHessianOffDiagonal;
flat out vec2 vUv;
flat out vec3 vDudx;
flat out vec3 vDvdx;
flat out vec4 vGlowMaterial;  // glow; material as float
flat out float vBody;
flat out ivec4 vEmissionTexture;
// realtime.particles.min_pixels: the flux of a sub-pixel sphere, in pixel areas times its
// emission (0: drawn as a sphere), and its centre in window coordinates (pixels).
flat out float vSplatFlux;
flat out vec2 vSplatCentre;
#endif

// A zero-area quad outside the clip volume: the particle is not drawn.
void dropQuad() {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    vOffset = vec2(0.0);
#ifndef SHADOW_PASS
    vQuadPoint = vec3(0.0);
#ifdef ELLIPSOID
    vQuadOffset = vec3(0.0);
#endif
#endif
}

void main() {
    int particle = gl_VertexID / 6;
#ifdef BODY_MASK
    if (bodyReplaced(toIndex(particles[particle].dvdxBody.w))) {
        dropQuad();
        return;
    }
#endif
    vec2 corner = QUAD_CORNERS[gl_VertexID % 6];
    vec4 pr = particles[particle].positionRadius;
    float r = pr.w;
    vRadius = r;
#ifndef SHADOW_PASS
    mat3 toEye = mat3(viewFromWorld);
    vec3 c = toEye * pr.xyz;
    vSplatFlux = 0.0;
    vSplatCentre = vec2(0.0);
#ifdef ELLIPSOID
    EllipsoidRecord e = ellipsoids[particle];
    mat3 axes = ellipsoidAxes(e, toEye);
    vec3 centre = c + toEye * ellipsoidShift(e);
    float d = length(centre);
    vec3 axis = centre / d;
    // A^T w / D: the ellipsoid's half-extent along the view axis over D. At 1 or above, part of
    // it lies beside or behind the eye (or holds it): drop it, as a sphere holding the eye.
    vec3 along = (axis * axes) / d;
    float den = 1.0 - dot(along, along);
    if (den <= 2e-4) {
        dropQuad();
        return;
    }
    vInverseAxes = inverseAxes(axes);
#else
    float d = length(c);
    if (d <= r * 1.0001) {
        // The eye is inside this sphere: drop it.
        dropQuad();
        return;
    }
    vec3 axis = c / d;
    // realtime.particles.min_pixels (misc.w): a sphere projected smaller than that radius in
    // pixels covers few pixel centres or none, so its light would flicker or vanish. It is drawn
    // instead as a splat of its flux (its projected area in pixels times its emission) over the
    // pixels within one of its centre, weighted by a bilinear tent, whose weights sum to 1
    // wherever the centre lies (gbuffer.frag). The quad must then reach those pixel centres, up
    // to sqrt(2) pixels away: its radius is at least 1.5 pixels. Off (0), the branch is never
    // taken and vSplatFlux stays 0.
    float projected = r * pixelsPerUnitAt(-c.z);
    if (misc.w > 0.0 && c.z < 0.0 && projected < misc.w) {
        vSplatFlux = 3.14159265 * projected * projected;
        vec4 clip = clipFromView * vec4(c, 1.0);
        vSplatCentre = (clip.xy / clip.w * 0.5 + 0.5) * viewport.xy;
        r = max(misc.w, 1.5) / pixelsPerUnitAt(-c.z);
        vRadius = r;
        if (d <= r * 1.0001) {
            dropQuad();
            return;
        }
    }
    // realtime.particles.halo_pixels (subpixel.x): a sphere projected smaller than that radius
    // gives its emitted light to its halo (halo.vert), added after shading; drawn here, it
    // emits nothing (vSplatFlux < 0).
    if (subpixel.x > 0.0 && c.z < 0.0 && projected < subpixel.x) vSplatFlux = -1.0;
#endif
    vCentreDistance = d;
    Particle p = particles[particle];
    vCentre = c;
    vNormal = p.normalU.xyz;
    vHessianDiagonal = p.hessianDiagonal.xyz;
    vHessianOffDiagonal = p.hessianOffDiagonal.xyz;
    vUv = vec2(p.normalU.w, p.dudxV.w);
    vDudx = p.dudxV.xyz;
    vDvdx = p.dvdxBody.xyz;
    vGlowMaterial = p.glowMaterial;
    vBody = p.dvdxBody.w;
    vEmissionTexture = materials[toIndex(p.glowMaterial.w)].emission;
    vec3 helper = abs(axis.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 across = normalize(cross(helper, axis));
    vec3 up = cross(axis, across);
#ifdef ELLIPSOID
    // The silhouette's extent along `across` is the pair of roots of
    // den X^2 + 2 D (a.w) X - D^2 (a.a) = 0, a = A^T across / D, w = A^T axis / D (= along).
    vec3 ax = (across * axes) / d, ay = (up * axes) / d;
    vec2 aw = vec2(dot(ax, along), dot(ay, along));
    vec2 mid = -d * aw / den;
    vec2 halfSize = d * sqrt(aw * aw + den * vec2(dot(ax, ax), dot(ay, ay))) / den;
    vOffset = mid + corner * halfSize;
    vQuadOffset = vOffset.x * across + vOffset.y * up;
    vQuadPoint = centre + vQuadOffset;
#else
    float halfSize = r * d / sqrt((d - r) * (d + r));
    vOffset = corner * halfSize;
    vQuadPoint = c + vOffset.x * across + vOffset.y * up;
#endif
    gl_Position = clipFromView * vec4(vQuadPoint, 1.0);
#else
#ifdef ELLIPSOID
    EllipsoidRecord e = ellipsoids[particle];
    mat3 axes = ellipsoidAxes(e, mat3(lightView));
    vInverseAxes = inverseAxes(axes);
    vec3 c = (lightView * vec4(pr.xyz + ellipsoidShift(e), 1.0)).xyz;
    // The half-extent along a unit direction u is |A^T u|: here the rows of A.
    vec2 halfSize = vec2(length(vec3(axes[0].x, axes[1].x, axes[2].x)),
                         length(vec3(axes[0].y, axes[1].y, axes[2].y)));
#else
    vec3 c = (lightView * vec4(pr.xyz, 1.0)).xyz;
    vec2 halfSize = vec2(r);
#endif
    vCentreDepth = -c.z;
    vOffset = corner * halfSize;
    gl_Position = lightClip * vec4(c.xy + vOffset, c.z, 1.0);
#endif
}
