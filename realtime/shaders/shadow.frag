// The shadow pass: the front of each impostor sphere seen along the light, as linear light
// depth in [0, 1] (an orthographic map has uniform precision: no logarithmic encoding).
#include "common.glsl"

in vec2 vOffset;
flat in float vCentreDepth;
flat in float vRadius;

void main() {
    float rho2 = dot(vOffset, vOffset);
    float r2 = vRadius * vRadius;
    if (rho2 >= r2) discard;
    float depth = vCentreDepth - sqrt(r2 - rho2);
    gl_FragDepth = clamp((depth - shadowRange.x) / (shadowRange.y - shadowRange.x), 0.0, 1.0);
}
