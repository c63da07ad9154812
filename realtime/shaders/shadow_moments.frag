// The filtered shadow maps, step 1: the depth map (linear light depth d in [0, 1]) turned into
// what the shade pass filters (shadow_filters.glsl): ESM_SEED d; ESM_WARP exp(c d); VSM d and
// d^2; EVSM exp(c+ d), exp(2 c+ d), -exp(-c- d), exp(-2 c- d). The exponents are kept below
// what a 32-bit float holds (realtime/settings.h, ShadowMapSettings).
layout(binding = 0) uniform sampler2D uDepthMap;  // Depth32F, read with texelFetch
uniform vec2 uExponents;                          // ESM: c, 0; EVSM: c+, c-

layout(location = 0) out vec4 outMoments;

void main() {
    float d = texelFetch(uDepthMap, ivec2(gl_FragCoord.xy), 0).r;
#if defined(ESM_SEED)
    outMoments = vec4(d, 0.0, 0.0, 0.0);
#elif defined(ESM_WARP)
    outMoments = vec4(exp(uExponents.x * d), 0.0, 0.0, 0.0);
#elif defined(VSM)
    outMoments = vec4(d, d * d, 0.0, 0.0);
#else  // EVSM
    float positive = exp(uExponents.x * d);
    float negative = -exp(-uExponents.y * d);
    outMoments = vec4(positive, positive * positive, negative, negative * negative);
#endif
}
