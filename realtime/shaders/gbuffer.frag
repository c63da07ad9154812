// The G-buffer pass: ray-impostor intersection per pixel (a sphere, or with ELLIPSOID an
// ellipsoid), depth in the selected encoding, and the particle's attributes: normal (the
// model of realtime.particles.normal, blended with the impostor's own), uv extrapolated to
// the hit point with d(uv)/dx, body and material, projected radius, emission (emission map at
// uv + blackbody glow).
// BODY_SPHERE (realtime.particles.body_sphere_pixels): a whole body as one sphere
// (gpu_scene.h, packBodySpheres): its own normal, uv its body-local spherical angles.
// BACK_LAYER (realtime.ao.layers = 2, realtime/ao_pass.cpp): the occlusion pass's second depth
// layer, the back of the body seen at each pixel: each impostor's far intersection, kept where
// its body is the one uFront holds there, the farthest of them by the depth test; the eye depth
// alone in the first target.
#include "common.glsl"
#include "textures.glsl"

in vec2 vOffset;
in vec3 vQuadPoint;
flat in float vCentreDistance;
flat in float vRadius;
#ifdef ELLIPSOID
in vec3 vQuadOffset;
flat in mat3 vInverseAxes;
#endif
flat in vec3 vCentre;
flat in vec3 vNormal;
flat in vec3 vHessianDiagonal;
flat in vec3 vHessianOffDiagonal;
flat in vec2 vUv;
flat in vec3 vDudx;
flat in vec3 vDvdx;
flat in vec4 vGlowMaterial;
flat in float vBody;
flat in ivec4 vEmissionTexture;
flat in float vSplatFlux;
flat in vec2 vSplatCentre;

layout(location = 0) out vec4 outNormalUv;  // world normal (octahedral), u, v
layout(location = 1) out vec4 outEmission;  // emission (linear RGB), 0
layout(location = 2) out vec4 outSurface;   // eye depth, body, projected radius (px), material
#ifdef BACK_LAYER
layout(binding = 6) uniform sampler2D uFront;  // the occlusion pass's surface: eye depth, body
#endif

void main() {
    // realtime.particles.min_pixels: a sub-pixel sphere's flux spread by a bilinear tent over
    // the pixels within one of its centre (impostor.vert). The tent's weights at the pixel
    // centres sum to 1 wherever the centre lies, so the image holds the sphere's flux whatever
    // its position: no loss and no flicker as it moves. Elsewhere the pixel is not covered.
    // realtime.particles.halo_pixels: a sphere whose halo carries its light (vSplatFlux < 0)
    // emits nothing here.
    float splat = vSplatFlux < 0.0 ? 0.0 : 1.0;
    if (vSplatFlux > 0.0) {
        vec2 tent = max(1.0 - abs(gl_FragCoord.xy - vSplatCentre), 0.0);
        splat = vSplatFlux * tent.x * tent.y;
        if (splat <= 0.0) discard;
    }
#ifdef ELLIPSOID
    // The eye ray as q + s dir from the quad point q, in the ellipsoid's unit-sphere space
    // o + s m with o = A^-1 (q - centre): o is of order 1 whatever the distance to the
    // particle, so the quadratic |o + s m|^2 = 1 has no large-number cancellation.
    vec3 dir = normalize(vQuadPoint);
    vec3 o = vInverseAxes * vQuadOffset;
    vec3 m = vInverseAxes * dir;
    float a = dot(m, m), b = dot(o, m);
    float disc = b * b - a * (dot(o, o) - 1.0);
    if (disc < 0.0) discard;
#ifdef BACK_LAYER
    float s = (-b + sqrt(disc)) / a;  // where the ray leaves the ellipsoid
#else
    float s = (-b - sqrt(disc)) / a;
#endif
    vec3 hit = vQuadPoint + s * dir;  // eye space
    // The normal of |A^-1 (x - centre)| = 1: A^-T times the hit point in unit-sphere space.
    vec3 impostorNormal = normalize(transpose(vInverseAxes) * (o + s * m));
#else
    // The eye ray through the quad point q: with rho = |q - c| in the plane perpendicular to
    // the centre direction, the ray passes the centre at distance D rho / sqrt(D^2 + rho^2)
    // and its closest approach lies at D^2 / sqrt(D^2 + rho^2). No large-number cancellation,
    // whatever the distance to the particle, and no product of two squares (D^2 rho^2
    // overflows a float once D and rho reach about 1e10 and 1e9, as in a scene of far/near
    // 1e11).
    float d2 = vCentreDistance * vCentreDistance;
    float rho2 = dot(vOffset, vOffset);
    float r2 = vRadius * vRadius;
    float miss2 = rho2 * (d2 / (d2 + rho2));
    if (miss2 >= r2) discard;
#ifdef BACK_LAYER
    float t = d2 / sqrt(d2 + rho2) + sqrt(r2 - miss2);  // where the ray leaves the sphere
#else
    float t = d2 / sqrt(d2 + rho2) - sqrt(r2 - miss2);
#endif
    vec3 hit = normalize(vQuadPoint) * t;  // eye space
    vec3 impostorNormal = (hit - vCentre) / vRadius;
#endif
    float z = -hit.z;
    if (z < cameraNear() || z > cameraFar()) discard;
    gl_FragDepth = windowDepth(z);
#ifdef BACK_LAYER
    vec4 front = texelFetch(uFront, ivec2(gl_FragCoord.xy), 0);
    if (front.y < 0.0 || abs(vBody - front.y) > 0.5) discard;
    outNormalUv = vec4(z, 0.0, 0.0, 0.0);
    return;
#endif

    mat3 worldFromView = transpose(mat3(viewFromWorld));
    vec3 offset = worldFromView * (hit - vCentre);
#ifdef BODY_SPHERE
    // The generated particles' uv (core::sphericalUv): longitude about the body's pole axis
    // (frame z) from its x axis -> u, latitude -> v, about the uv frame's origin; the frame's
    // columns come in vNormal, vDudx, vDvdx, the origin relative to the centre in
    // vHessianDiagonal.
    vec3 local = transpose(mat3(vNormal, vDudx, vDvdx)) * (offset - vHessianDiagonal);
    float u = fract(atan(local.y, local.x) / 6.28318531);
    float v = atan(local.z, length(local.xy)) / 3.14159265 + 0.5;
#else
    float u = fract(vUv.x + dot(vDudx, offset));
    float v = clamp(vUv.y + dot(vDvdx, offset), 0.0, 1.0);
#endif
    vec3 emission = sampleTexture(vEmissionTexture, vec2(u, v)) + vGlowMaterial.rgb;
#if defined(EMITTERS_ONLY)
    // The emissive pass's emitter target ("ssem_target"): only what emits.
    if (emission == vec3(0.0)) discard;
#endif
    // realtime.particles.normal: "field", the colour field's gradient modelled to first order
    // over the impostor (realtime/field_normal.h), misc.z = 0; "blend", the particle's normal
    // (no Hessian) tilted towards the impostor's own normal by misc.z: at a surface point the
    // particle's own kernel adds a gradient along (x - x_i), which the normal taken at the
    // particle's centre lacks; "sphere", the impostor's own normal, misc.z = 1.
#ifdef BODY_SPHERE
    outNormalUv = vec4(octEncode(normalize(worldFromView * impostorNormal)), u, v);
#else
    vec3 d = vHessianDiagonal, h = vHessianOffDiagonal;
    vec3 model = vNormal + vec3(dot(vec3(d.x, h.x, h.y), offset), dot(vec3(h.x, d.y, h.z), offset),
                                dot(vec3(h.y, h.z, d.z), offset));
    outNormalUv =
        vec4(octEncode(normalize(mix(model, worldFromView * impostorNormal, misc.z))), u, v);
#endif
    outEmission = vec4(emission * splat, 0.0);
    outSurface = vec4(z, vBody, vRadius * pixelsPerUnitAt(-vCentre.z), vGlowMaterial.w);
}
