// Bilateral filter of eye depth (van der Laan, Green & Sainz 2009; Green 2010; NVIDIA FleX's
// weights): spatial weight exp(-(d / R)^2) with R the projected particle radius times
// uRadius (at most uMaxRadiusPx), range weight exp(-dz^2 / 2 sigma^2) with sigma uDepthSigma
// particle radii. SEPARABLE: one direction (uDirection) per pass; else the full 2-D kernel.
// Only pixels of the centre's body count.
#include "common.glsl"
#include "surface_common.glsl"
#include "convert.glsl"

uniform float uRadius;       // kernel radius / projected particle radius
uniform float uDepthSigma;   // range sigma / particle radius
uniform float uMaxRadiusPx;  // cap on the kernel radius, pixels
const int MAX_TAPS = 64;     // surface.bilateral.max_radius_px's largest
uniform vec2 uDirection;     // SEPARABLE: (1, 0) or (0, 1)

layout(location = 0) out vec4 outSurface;

float gDepth, gBody, gInvRadius2, gInv2Sigma2, gSum, gWeight;

void tap(ivec2 p, ivec2 o) {
    vec4 t = surfaceAt(p + o);
    if (t.y != gBody) return;
    float dz = t.x - gDepth;
    float w = exp(-float(dot(o, o)) * gInvRadius2 - dz * dz * gInv2Sigma2);
    gSum += w * t.x;
    gWeight += w;
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 s = texelFetch(uSurface, p, 0);
    outSurface = s;
    if (s.y < 0.0) return;
    float radiusPx = min(uMaxRadiusPx, uRadius * s.z);
    int taps = clampToInt(ceil(radiusPx), 0, MAX_TAPS);  // NaN: 0
    if (taps < 1) return;
    float sigma = uDepthSigma * s.z / pixelsPerUnitAt(s.x);
    gDepth = s.x;
    gBody = s.y;
    gInvRadius2 = 1.0 / (radiusPx * radiusPx);
    gInv2Sigma2 = 1.0 / (2.0 * sigma * sigma);
    gSum = s.x;
    gWeight = 1.0;
#ifdef SEPARABLE
    ivec2 d = ivec2(uDirection);
    for (int k = 1; k <= taps; ++k) {
        tap(p, k * d);
        tap(p, -k * d);
    }
#else
    for (int j = -taps; j <= taps; ++j)
        for (int i = -taps; i <= taps; ++i)
            if (i != 0 || j != 0) tap(p, ivec2(i, j));
#endif
    outSurface.x = gSum / gWeight;
}
