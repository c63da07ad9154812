// Screen-Space Surface Smoothing: the seed's "smart blur" of uv, normal and emission.
//  - only pixels of the same body (id) and within a depth limit of the centre pixel;
//  - symmetric exclusion: samples come in pairs p + o, p - o and a pair counts only when both
//    are valid, so the kernel stays centred and a linear ramp of uv stays a linear ramp;
//  - the radius is the projected particle radius times a scale, shortened by the surface
//    normal: a disc on the surface projects to an ellipse squeezed by n_z along n_xy, so the
//    weight of a screen offset o uses the surface distance s^2 = |o|^2 + (o . n_xy / n_z)^2;
//  - u is averaged as an offset from the centre's u wrapped to [-0.5, 0.5], so the texture
//    seam (u = 0 = 1) does not pull pixels towards u = 0.5.
// State being smoothed: A = (octahedral normal, u, v) and, with EMISSION, the emission; static:
// S = (eye depth, body, projected radius in pixels, material) from the G-buffer.
// Needs common.glsl.

layout(binding = 0) uniform sampler2D uNormalUv;
layout(binding = 1) uniform sampler2D uEmission;
layout(binding = 2) uniform sampler2D uSurface;

uniform float uRadiusScale;  // blur radius / projected particle radius
uniform float uDepthLimit;   // in particle radii
uniform int uMaxTaps;        // samples on each side of the centre (per axis in 2-D)

layout(location = 0) out vec4 outNormalUv;
#ifdef EMISSION
layout(location = 1) out vec4 outEmission;
#endif

// Below this |n_z| the kernel stops shrinking, so silhouette pixels still get some smoothing.
const float MIN_FACING = 0.1;

ivec2 gSize;
float gBody, gDepth, gDepthLimit, gInv2Sigma2, gRadiusPx, gU;
vec2 gTilt;  // n_xy / n_z (eye space): offsets along it are foreshortened
vec3 gSumNormal, gSumEmission;
float gSumDu, gSumV, gSumWeight;

// Sets up the kernel of the centre pixel; false when it does not blur (background, or a
// radius under one pixel).
bool beginBlur(ivec2 p, vec4 a) {
    gSize = textureSize(uSurface, 0);
    vec4 s = texelFetch(uSurface, p, 0);
    if (s.y < 0.0) return false;
    gBody = s.y;
    gDepth = s.x;
    gDepthLimit = uDepthLimit * s.z / pixelsPerUnitAt(s.x);
    gRadiusPx = uRadiusScale * s.z;
    float sigma = 0.5 * gRadiusPx;
    gInv2Sigma2 = 1.0 / (2.0 * sigma * sigma);
    vec3 normal = octDecode(a.xy);
    vec3 n = mat3(viewFromWorld) * normal;
    gTilt = n.xy / max(abs(n.z), MIN_FACING);
    gU = a.z;
    gSumNormal = normal;
    gSumDu = 0.0;
    gSumV = a.w;
    gSumWeight = 1.0;
#ifdef EMISSION
    gSumEmission = texelFetch(uEmission, p, 0).rgb;
#endif
    return gRadiusPx >= 1.0;
}

bool valid(ivec2 q) {
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, gSize))) return false;
    vec2 s = texelFetch(uSurface, q, 0).xy;
    return s.y == gBody && abs(s.x - gDepth) < gDepthLimit;
}

float squaredSurfaceDistance(vec2 offset) {
    float along = dot(offset, gTilt);
    return dot(offset, offset) + along * along;
}

void accumulate(ivec2 q, float w) {
    vec4 a = texelFetch(uNormalUv, q, 0);
    float du = a.z - gU;
    du -= round(du);
    gSumNormal += w * octDecode(a.xy);
    gSumDu += w * du;
    gSumV += w * a.w;
#ifdef EMISSION
    gSumEmission += w * texelFetch(uEmission, q, 0).rgb;
#endif
    gSumWeight += w;
}

// Adds the pair p +- o when both ends are valid.
void pair(ivec2 p, ivec2 o) {
    if (o == ivec2(0) || !valid(p + o) || !valid(p - o)) return;
    float w = exp(-squaredSurfaceDistance(vec2(o)) * gInv2Sigma2);
    accumulate(p + o, w);
    accumulate(p - o, w);
}

void endBlur(vec4 centre) {
    float len = length(gSumNormal);
    vec3 normal = len > 0.0 ? gSumNormal / len : octDecode(centre.xy);
    outNormalUv = vec4(octEncode(normal), fract(gU + gSumDu / gSumWeight), gSumV / gSumWeight);
#ifdef EMISSION
    outEmission = vec4(gSumEmission / gSumWeight, 0.0);
#endif
}
