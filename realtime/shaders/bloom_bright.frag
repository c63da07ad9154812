// Bloom, step 1: the radiance above the threshold, at half resolution. One bilinear tap at
// the shared corner of four full-resolution pixels averages them (the beauty is sampled
// linearly), then the threshold applies.
layout(binding = 0) uniform sampler2D uBeauty;  // linear beauty (rgb), full resolution, linear filtering
uniform float uThreshold;

layout(location = 0) out vec4 outColor;

void main() {
    vec2 uv = (gl_FragCoord.xy * 2.0) / vec2(textureSize(uBeauty, 0));
    outColor = vec4(max(textureLod(uBeauty, uv, 0.0).rgb - uThreshold, 0.0), 1.0);
}
