// One triangle that covers the viewport: (-1,-1), (3,-1), (-1,3), at clip depth uDepth.
// Passes that only touch covered pixels put it at the background's depth and test against the
// G-buffer's depth buffer, so background pixels are rejected before the fragment shader.
uniform float uDepth;

void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, uDepth, 1.0);
}
