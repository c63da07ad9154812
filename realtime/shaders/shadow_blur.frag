// The filtered shadow maps, step 2: one direction of a separable box blur, texels i with
// |i| <= uRadius weighing 1 and the outermost pair, at ceil(uRadius), the radius's fraction.
// The map's edge is clamped (texels beyond it repeat the edge).
#include "convert.glsl"
layout(binding = 0) uniform sampler2D uMap;  // the moments (shadow_moments.frag), texelFetch
uniform ivec2 uDirection;                    // (1, 0), then (0, 1)
uniform float uRadius;                       // texels, > 0
const int MAX_RADIUS = 16;                   // shadow_map.blur_radius's largest

layout(location = 0) out vec4 outMoments;

vec4 tap(ivec2 p, int offset, ivec2 size) {
    return texelFetch(uMap, clamp(p + uDirection * offset, ivec2(0), size - ivec2(1)), 0);
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(uMap, 0);
    int whole = clampToInt(floor(uRadius), 0, MAX_RADIUS);
    float fraction = uRadius - float(whole);
    vec4 sum = tap(p, 0, size);
    for (int i = 1; i <= whole; ++i) sum += tap(p, i, size) + tap(p, -i, size);
    if (fraction > 0.0) sum += fraction * (tap(p, whole + 1, size) + tap(p, -whole - 1, size));
    outMoments = sum / (1.0 + 2.0 * uRadius);
}
