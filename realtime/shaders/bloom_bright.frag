// Bloom, step 1: the radiance above the threshold, at half resolution (a 2x2 box).
layout(binding = 0) uniform sampler2D uBeauty;  // linear beauty (rgb), full resolution
uniform float uThreshold;

layout(location = 0) out vec4 outColor;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy) * 2;
    ivec2 last = textureSize(uBeauty, 0) - 1;
    vec3 sum = vec3(0.0);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i)
            sum += max(texelFetch(uBeauty, min(p + ivec2(i, j), last), 0).rgb - uThreshold, 0.0);
    outColor = vec4(sum * 0.25, 1.0);
}
