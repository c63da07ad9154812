// Bloom, step 2: each level is the previous one at half size; one bilinear tap at the shared
// corner of four texels averages them.
layout(binding = 0) uniform sampler2D uSource;  // the larger level, linear filtering

layout(location = 0) out vec4 outColor;

void main() {
    vec2 uv = (gl_FragCoord.xy * 2.0) / vec2(textureSize(uSource, 0));
    outColor = vec4(textureLod(uSource, uv, 0.0).rgb, 1.0);
}
