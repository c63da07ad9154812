// The error split (realtime/error_split.cpp): the depth buffer of the reference's surface, so
// that the passes that read only covered pixels (coveredOnlyState) see its coverage. Writes
// the window depth of each covered pixel's eye depth in the selected encoding.
#include "common.glsl"

layout(binding = 2) uniform sampler2D uSurface;  // eye depth (+inf background), body

void main() {
    vec4 s = texelFetch(uSurface, ivec2(gl_FragCoord.xy), 0);
    if (s.y < 0.0) discard;
    gl_FragDepth = windowDepth(s.x);
}
