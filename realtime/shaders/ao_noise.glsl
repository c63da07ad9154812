// The occlusion passes' per-pixel noise (ao.frag: slice rotation and step jitter; ao_traced.frag:
// the rays' rotation and jitter), two numbers in [0, 1) as realtime.ao.noise chooses:
// NOISE_WHITE (a hash), NOISE_IGN (interleaved gradient noise, Jimenez 2014), NOISE_BLUE (a
// void-and-cluster texture at texture unit 5, realtime/blue_noise.h).
#ifdef NOISE_BLUE
layout(binding = 5) uniform sampler2D uBlueNoise;  // R32F ranks in [0, 1), tiled
#endif

vec2 noise(ivec2 p) {
#if defined(NOISE_BLUE)
    ivec2 size = textureSize(uBlueNoise, 0);
    float b = texelFetch(uBlueNoise, p % size, 0).r;
    return vec2(b, fract(b + 0.61803398875));
#elif defined(NOISE_IGN)
    vec2 q = vec2(p);
    float a = fract(52.9829189 * fract(dot(q, vec2(0.06711056, 0.00583715))));
    float b = fract(52.9829189 * fract(dot(q + vec2(5.588238), vec2(0.06711056, 0.00583715))));
    return vec2(a, b);
#else
    // A 2-D integer hash (pcg2d, Jarzynski & Olano 2020).
    uvec2 v = uvec2(p) * 1664525u + 1013904223u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v ^= v >> 16u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v ^= v >> 16u;
    return vec2(v >> 8u) * (1.0 / 16777216.0);
#endif
}
