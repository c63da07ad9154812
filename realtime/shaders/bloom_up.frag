// Bloom, step 3: from the smallest level up, each level adds the next smaller one, upsampled
// with a 3x3 tent of bilinear taps (blending is additive).
layout(binding = 0) uniform sampler2D uSource;  // the smaller level, linear filtering
uniform vec2 uTargetTexel;                      // 1 / size of the level written

layout(location = 0) out vec4 outColor;

void main() {
    vec2 uv = gl_FragCoord.xy * uTargetTexel;
    vec2 d = uTargetTexel;
    vec3 c = textureLod(uSource, uv, 0.0).rgb * 4.0;
    c += (textureLod(uSource, uv + vec2(d.x, 0.0), 0.0).rgb +
          textureLod(uSource, uv - vec2(d.x, 0.0), 0.0).rgb +
          textureLod(uSource, uv + vec2(0.0, d.y), 0.0).rgb +
          textureLod(uSource, uv - vec2(0.0, d.y), 0.0).rgb) * 2.0;
    c += textureLod(uSource, uv + d, 0.0).rgb + textureLod(uSource, uv - d, 0.0).rgb +
         textureLod(uSource, uv + vec2(d.x, -d.y), 0.0).rgb +
         textureLod(uSource, uv + vec2(-d.x, d.y), 0.0).rgb;
    outColor = vec4(c / 16.0, 1.0);
}
