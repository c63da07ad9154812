// Screen-Space Surface Smoothing, one pass: one direction of the separable kernel
// (SEPARABLE, uDirection = (1, 0) then (0, 1): the default) or the full 2-D kernel
// (realtime.ssss.separable = false), to measure the streaks the separable one makes.
// The kernel is in ssss_common.glsl.
#include "common.glsl"
#include "ssss_common.glsl"
#include "convert.glsl"

uniform vec2 uDirection;  // SEPARABLE: (1, 0) or (0, 1)

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 a = texelFetch(uNormalUv, p, 0);
    outNormalUv = a;
#ifdef EMISSION
    outEmission = texelFetch(uEmission, p, 0);
#endif
    if (!beginBlur(p, a)) return;
#ifdef SEPARABLE
    // Pixels along the direction per pixel of surface distance.
    float along = dot(uDirection, gTilt);
    float radius = gRadiusPx / sqrt(1.0 + along * along);
    int taps = clampToInt(radius, 0, uMaxTaps);
    float stepPx = taps > 0 ? radius / float(taps) : 0.0;
    for (int k = 1; k <= taps; ++k) pair(p, saturateToInt(round(uDirection * (float(k) * stepPx))));
#else
    int taps = clampToInt(gRadiusPx, 0, uMaxTaps);
    float stepPx = gRadiusPx / float(taps);
    float limit2 = gRadiusPx * gRadiusPx;
    // Half of the grid (j > 0, or j == 0 and i > 0): each offset stands for its pair.
    for (int j = 0; j <= taps; ++j) {
        for (int i = -taps; i <= taps; ++i) {
            if (j == 0 && i <= 0) continue;
            ivec2 o = saturateToInt(round(vec2(i, j) * stepPx));
            if (squaredSurfaceDistance(vec2(o)) <= limit2) pair(p, o);
        }
    }
#endif
    endBlur(a);
}
