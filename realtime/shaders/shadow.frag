// The shadow pass: the front of each impostor (a sphere, or with ELLIPSOID an ellipsoid) seen
// along the light, as linear light depth in [0, 1] (an orthographic map has uniform precision:
// no logarithmic encoding).
#include "common.glsl"

in vec2 vOffset;
flat in float vCentreDepth;
flat in float vRadius;
#ifdef ELLIPSOID
flat in mat3 vInverseAxes;
#endif

void main() {
#ifdef ELLIPSOID
    // The ray (vOffset, s) towards the light (+z, light depth falling) in the ellipsoid's
    // unit-sphere space: |o + s m|^2 = 1, the larger root nearest the light.
    vec3 o = vInverseAxes * vec3(vOffset, 0.0);
    vec3 m = vInverseAxes[2];
    float a = dot(m, m), b = dot(o, m);
    float disc = b * b - a * (dot(o, o) - 1.0);
    if (disc < 0.0) discard;
    float depth = vCentreDepth - (sqrt(disc) - b) / a;
#else
    float rho2 = dot(vOffset, vOffset);
    float r2 = vRadius * vRadius;
    if (rho2 >= r2) discard;
    float depth = vCentreDepth - sqrt(r2 - rho2);
#endif
    gl_FragDepth = clamp((depth - shadowRange.x) / (shadowRange.y - shadowRange.x), 0.0, 1.0);
}
