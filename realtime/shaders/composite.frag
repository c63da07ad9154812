// Post: beauty plus bloom (BLOOM), tonemapped (core::tonemap) into display values in [0, 1].
#include "tonemap.glsl"

layout(binding = 0) uniform sampler2D uBeauty;  // linear beauty, full resolution
layout(binding = 1) uniform sampler2D uBloom;   // bloom level 0 (half resolution), linear filtering
uniform float uStrength;
uniform float uExposure;

layout(location = 0) out vec4 outDisplay;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 c = texelFetch(uBeauty, p, 0).rgb;
#ifdef BLOOM
    c += uStrength * texture(uBloom, gl_FragCoord.xy / vec2(textureSize(uBeauty, 0))).rgb;
#endif
    outDisplay = vec4(tonemap(c, uExposure), 1.0);
}
