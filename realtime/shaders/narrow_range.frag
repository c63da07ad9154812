// Narrow-range filter of eye depth (Truong & Yuksel 2018), with positive eye depth d:
//  - a Gaussian of sigma R / 3 over R = uRadius projected particle radii (at most
//    uMaxRadiusPx; uFixedRadiusPx when > 0: the paper's final 2-D pass of 4 pixels);
//  - the range [d0 - delta, d0 + delta] (delta = uThreshold particle radii): a sample nearer
//    than it is dropped, and its mirror about the centre with it (bias correction); one beyond
//    it, the background included, counts as d0 + mu (uClamp particle radii), so silhouettes
//    round off instead of keeping the spheres' edges; one outside the image is dropped with its
//    mirror;
//  - every sample within the range widens it to its own depth +- delta (range expansion), so
//    a slope seen at a grazing angle is followed, not cut;
//  - another body's samples within the range are dropped with their mirror.
// SEPARABLE: one direction (uDirection) per pass, a range per side; else rings of growing
// radius, one shared range.
#include "common.glsl"
#include "surface_common.glsl"
#include "convert.glsl"

uniform float uRadius;         // filter size / projected particle radius
uniform float uThreshold;      // delta / particle radius
uniform float uClamp;          // mu / particle radius
uniform float uMaxRadiusPx;    // cap on the filter size, pixels
uniform float uFixedRadiusPx;  // > 0: this filter size instead
const int MAX_TAPS = 256;      // surface.narrow_range.max_radius_px's largest
uniform vec2 uDirection;       // SEPARABLE: (1, 0) or (0, 1)

layout(location = 0) out vec4 outSurface;

float gBody, gDelta, gClamped;

// Sample q's depth for the filter: `dropped` when it lies in front of [lo, hi] or is another
// body's within it; the clamped depth when it lies behind (the background, +inf, included), so
// a body in front of another rounds off over it as over the background. Widens the range.
// Outside the image nothing is known: the surface may go on there, so the sample is dropped
// with its mirror (read as background, it would round off every body the image's edge cuts).
float classify(ivec2 q, inout float lo, inout float hi, out bool dropped) {
    dropped = !inImage(q);
    if (dropped) return 0.0;
    vec4 t = surfaceAt(q);
    float z = t.x;
    dropped = z < lo;
    if (dropped) return 0.0;
    if (z > hi) return gClamped;
    dropped = t.y != gBody;
    if (dropped) return 0.0;
    lo = min(lo, z - gDelta);
    hi = max(hi, z + gDelta);
    return z;
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 s = texelFetch(uSurface, p, 0);
    outSurface = s;
    if (s.y < 0.0) return;
    float radiusPx = uFixedRadiusPx > 0.0 ? uFixedRadiusPx : min(uMaxRadiusPx, uRadius * s.z);
    int taps = clampToInt(ceil(radiusPx), 0, MAX_TAPS);  // NaN: 0
    if (taps < 1) return;
    float sigma = float(taps) / 3.0;
    float inv2Sigma2 = 1.0 / (2.0 * sigma * sigma);
    float r = s.z / pixelsPerUnitAt(s.x);
    gBody = s.y;
    gDelta = uThreshold * r;
    gClamped = s.x + uClamp * r;
    float sum = s.x, weight = 1.0;
#ifdef SEPARABLE
    ivec2 d = ivec2(uDirection);
    float lo[2] = float[2](s.x - gDelta, s.x - gDelta);
    float hi[2] = float[2](s.x + gDelta, s.x + gDelta);
    for (int k = 1; k <= taps; ++k) {
        bool dropA, dropB;
        float za = classify(p + k * d, lo[0], hi[0], dropA);
        float zb = classify(p - k * d, lo[1], hi[1], dropB);
        if (dropA || dropB) continue;
        float g = exp(-float(k * k) * inv2Sigma2);
        sum += g * (za + zb);
        weight += 2.0 * g;
    }
#else
    float lo = s.x - gDelta, hi = s.x + gDelta;
    for (int k = 1; k <= taps; ++k) {
        // Half of the ring max(|i|, |j|) = k, each offset standing for its mirrored pair:
        // the top row, the right column from j = 0 and the left column above j = 0.
        for (int n = 0; n < 4 * k; ++n) {
            ivec2 o = n <= 2 * k       ? ivec2(n - k, k)
                      : n <= 3 * k     ? ivec2(k, n - 2 * k - 1)
                                       : ivec2(-k, n - 3 * k);
            bool dropA, dropB;
            float za = classify(p + o, lo, hi, dropA);
            float zb = classify(p - o, lo, hi, dropB);
            if (dropA || dropB) continue;
            float g = exp(-float(dot(o, o)) * inv2Sigma2);
            sum += g * (za + zb);
            weight += 2.0 * g;
        }
    }
#endif
    outSurface.x = sum / weight;
}
