// One camera-facing quad per particle (six vertices, gl_VertexID / 6 = the particle), sized
// so that it covers the sphere's silhouette; the fragment shader intersects the sphere.
//
// Camera pass: the quad lies in the plane through the centre perpendicular to the direction
// eye -> centre. The silhouette cone (half-angle asin(r / D)) cuts that plane in a circle of
// radius r D / sqrt(D^2 - r^2), which the quad circumscribes.
// SHADOW_PASS: orthographic from the light; the quad is perpendicular to the light, half-size r.
#include "common.glsl"
#include "particles.glsl"
#ifndef SHADOW_PASS
#include "textures.glsl"
#endif

out vec2 vOffset;           // position in the quad plane relative to the centre, scene units
#ifndef SHADOW_PASS
out vec3 vQuadPoint;        // eye-space position on the quad
flat out float vCentreDistance;  // D: distance eye -> centre
#else
flat out float vCentreDepth;     // light-space depth of the centre
#endif
flat out float vRadius;
#ifndef SHADOW_PASS
// The particle's attributes, fetched once per vertex rather than once per fragment.
flat out vec3 vCentre;        // eye space
flat out vec3 vNormal;        // world (field_normal.h: not unit)
flat out vec3 vHessianDiagonal;
flat out vec3 vHessianOffDiagonal;
flat out vec2 vUv;
flat out vec3 vDudx;
flat out vec3 vDvdx;
flat out vec4 vGlowMaterial;  // glow; material as float
flat out float vBody;
flat out ivec4 vEmissionTexture;
#endif

void main() {
    int particle = gl_VertexID / 6;
    vec2 corner = QUAD_CORNERS[gl_VertexID % 6];
    vec4 pr = particles[particle].positionRadius;
    float r = pr.w;
    vRadius = r;
#ifndef SHADOW_PASS
    vec3 c = mat3(viewFromWorld) * pr.xyz;
    float d = length(c);
    vCentreDistance = d;
    if (d <= r * 1.0001) {
        // The eye is inside this sphere: drop it (a zero-area quad outside the clip volume).
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        vOffset = vec2(0.0);
        vQuadPoint = vec3(0.0);
        return;
    }
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
    vEmissionTexture = materials[int(p.glowMaterial.w)].emission;
    vec3 axis = c / d;
    vec3 helper = abs(axis.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 across = normalize(cross(helper, axis));
    vec3 up = cross(axis, across);
    float halfSize = r * d / sqrt((d - r) * (d + r));
    vOffset = corner * halfSize;
    vQuadPoint = c + vOffset.x * across + vOffset.y * up;
    gl_Position = clipFromView * vec4(vQuadPoint, 1.0);
#else
    vec3 c = (lightView * vec4(pr.xyz, 1.0)).xyz;
    vCentreDepth = -c.z;
    vOffset = corner * r;
    gl_Position = lightClip * vec4(c.xy + vOffset, c.z, 1.0);
#endif
}
