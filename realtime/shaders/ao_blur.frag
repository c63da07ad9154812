// One direction of the ambient occlusion's separable blur (realtime/ao_pass.cpp): Gaussian
// weights (sigma = half the radius) over the covered pixels within uRadius; AO_DEPTH_AWARE
// also weighs each tap by its depth's closeness, exp(-(dz / (0.02 z))^2), and drops taps of
// another body, so that occlusion does not bleed across a silhouette. RGB: the same over the
// three channels of the emissive light's irradiance (realtime/emissive_pass.cpp).
#include "common.glsl"

#ifdef RGB
#define Value vec3
#define pick(t) (t).rgb
#else
#define Value float
#define pick(t) (t).r
#endif

layout(binding = 0) uniform sampler2D uOpen;     // the open fraction (r), RGB: irradiance
layout(binding = 2) uniform sampler2D uSurface;  // eye depth, body
uniform ivec2 uDirection;                        // (1, 0), then (0, 1)
uniform int uRadius;                             // pixels, >= 1

layout(location = 0) out vec4 outOpen;

// Relative depth difference at which a depth-aware tap's weight falls to 1/e.
const float DEPTH_SCALE = 0.02;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = ivec2(viewport.xy);
    vec4 centre = texelFetch(uSurface, p, 0);
    float sigma = 0.5 * float(uRadius);
    Value sum = Value(0.0);
    float weights = 0.0;
    for (int i = -uRadius; i <= uRadius; ++i) {
        ivec2 q = p + uDirection * i;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        vec4 s = texelFetch(uSurface, q, 0);
        if (s.y < 0.0) continue;
        float w = exp(-0.5 * float(i * i) / (sigma * sigma));
#ifdef AO_DEPTH_AWARE
        if (s.y != centre.y) continue;
        float dz = (s.x - centre.x) / (DEPTH_SCALE * centre.x);
        w *= exp(-dz * dz);
#endif
        sum += w * pick(texelFetch(uOpen, q, 0));
        weights += w;
    }
    Value value = weights > 0.0 ? sum / weights : pick(texelFetch(uOpen, p, 0));
#ifdef RGB
    outOpen = vec4(value, 0.0);
#else
    outOpen = vec4(value);
#endif
}
