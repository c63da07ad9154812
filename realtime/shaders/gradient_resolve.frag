// realtime.particles.normal = "gradient", second half: the normal is -grad c / |grad c| where
// the splatted gradient is not zero, else the G-buffer's own; uv are kept.
#include "common.glsl"

layout(binding = 0) uniform sampler2D uNormalUv;  // G-buffer: normal (octahedral), u, v
layout(binding = 1) uniform sampler2D uGradient;  // gradient_splat.frag's sum

layout(location = 0) out vec4 outNormalUv;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 a = texelFetch(uNormalUv, p, 0);
    vec3 g = texelFetch(uGradient, p, 0).xyz;
    float length2 = dot(g, g);
    outNormalUv = length2 > 0.0 ? vec4(octEncode(-g * inversesqrt(length2)), a.zw) : a;
}
