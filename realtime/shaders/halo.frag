// realtime.particles.halo_pixels (realtime/halo_pass.cpp, halo.vert): a sub-pixel emitter's
// flux spread over the pixels by a normalised Gaussian, added to the linear beauty where no
// surface nearer than the emitter's front hides it.
#include "common.glsl"

layout(binding = 2) uniform sampler2D uSurface;  // eye depth (+inf background), body, ...

flat in vec3 vFlux;
flat in vec2 vCentre;
flat in float vSigma;
flat in float vFrontDepth;

layout(location = 0) out vec4 outBeauty;

void main() {
    // The emitter's own sphere lies at or behind its front; a surface nearer by more than a
    // float's rounding hides the halo there.
    if (texelFetch(uSurface, ivec2(gl_FragCoord.xy), 0).x < vFrontDepth * (1.0 - 1e-5)) discard;
    vec2 offset = gl_FragCoord.xy - vCentre;
    float s2 = vSigma * vSigma;
    float weight = exp(-0.5 * dot(offset, offset) / s2) / (6.28318531 * s2);
    outBeauty = vec4(vFlux * weight, 0.0);  // a: the sun's visibility, unchanged
}
