// After a depth filter: normals rebuilt from the filtered eye depth (surface_common.glsl's
// normalFromDepth); uv is kept, background pixels are copied.
#include "common.glsl"
#include "surface_common.glsl"

layout(location = 0) out vec4 outNormalUv;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 a = texelFetch(uNormalUv, p, 0);
    outNormalUv = a;
    vec4 s = texelFetch(uSurface, p, 0);
    if (s.y < 0.0) return;
    outNormalUv.xy = octEncode(normalFromDepth(p, s.y, octDecode(a.xy)));
}
