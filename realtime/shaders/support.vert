// One camera-facing quad per particle covering its kernel's support sphere (radius 2 h), as
// impostor.vert covers the impostor sphere; a support that holds the eye covers the whole
// viewport. For passes that add each particle's share of the colour field to the surface
// points the G-buffer found. The quad's depth is the support's nearest eye depth (at least
// near) in the selected encoding, constant over the quad: tested against the G-buffer's depth,
// pixels whose surface lies in front of the whole support (deep particles, most of a body's)
// are rejected before the fragment shader runs.
#include "common.glsl"
#include "kernels.glsl"

// Corners of the two triangles of a quad, in quad coordinates.
const vec2 CORNERS[6] = vec2[](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0),
                               vec2(-1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, 1.0));

flat out int vKernel;

void main() {
    vKernel = gl_VertexID / 6;
    vec2 corner = CORNERS[gl_VertexID % 6];
    vec4 ps = kernels[vKernel].positionSupport;
    float r = ps.w;
    vec3 c = mat3(viewFromWorld) * ps.xyz;
    float d = length(c);
    float front = max(cameraNear(), -c.z - r);
#if defined(DEPTH_REVERSED)
    float ndcDepth = windowDepth(front);  // clip range [0, 1]
#else
    float ndcDepth = 2.0 * windowDepth(front) - 1.0;
#endif
    if (d <= r * 1.0001) {
        gl_Position = vec4(corner, ndcDepth, 1.0);
        return;
    }
    vec3 axis = c / d;
    vec3 helper = abs(axis.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 across = normalize(cross(helper, axis));
    vec3 up = cross(axis, across);
    float halfSize = r * d / sqrt((d - r) * (d + r));
    vec3 q = c + corner.x * halfSize * across + corner.y * halfSize * up;
    gl_Position = clipFromView * vec4(q, 1.0);
    gl_Position.z = ndcDepth * gl_Position.w;
}
