// Screen-space curvature flow (van der Laan, Green & Sainz 2009), one explicit step of
// dz/dt = H with positive eye depth z: the mean curvature H of the surface z(x, y) from the
// paper's screen-space formula (9 taps), and a step of uTimeStep pixels^2 of diffusion on a
// flat surface (the depth moves by uTimeStep * (Cx + Cy) z H), stable up to 0.25 at every
// depth. Derivatives across an edge (a neighbour of another body or the background, or a
// depth step over uDepthLimit particle radii) count as zero, as the paper: the silhouette is
// not pulled towards what lies behind it.
#include "common.glsl"
#include "surface_common.glsl"

uniform float uTimeStep;    // pixels^2 per step
uniform float uDepthLimit;  // particle radii

layout(location = 0) out vec4 outSurface;

float gBody, gDepth;

// Depth of the neighbour, and whether it lies on the same body.
float neighbour(ivec2 q, out bool same) {
    vec4 t = surfaceAt(q);
    same = t.y == gBody;
    return same ? t.x : gDepth;
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 s = texelFetch(uSurface, p, 0);
    outSurface = s;
    if (s.y < 0.0) return;
    gBody = s.y;
    gDepth = s.x;
    float z = s.x;
    float limit = uDepthLimit * s.z / pixelsPerUnitAt(z);
    bool okL, okR, okD, okU, okA, okB, okC, okE;
    float zl = neighbour(p + ivec2(-1, 0), okL), zr = neighbour(p + ivec2(1, 0), okR);
    float zd = neighbour(p + ivec2(0, -1), okD), zu = neighbour(p + ivec2(0, 1), okU);
    float zpp = neighbour(p + ivec2(1, 1), okA), zmm = neighbour(p + ivec2(-1, -1), okB);
    float zpm = neighbour(p + ivec2(1, -1), okC), zmp = neighbour(p + ivec2(-1, 1), okE);

    float zx = 0.5 * (zr - zl), zxx = zr + zl - 2.0 * z;
    if (!okL || !okR || abs(zx) > limit) zx = zxx = 0.0;
    float zy = 0.5 * (zu - zd), zyy = zu + zd - 2.0 * z;
    if (!okD || !okU || abs(zy) > limit) zy = zyy = 0.0;
    float zxy = 0.25 * (zpp + zmm - zpm - zmp);
    if (!(okA && okB && okC && okE) || abs(zxy) > limit) zxy = 0.0;

    // Cx = 2 / (W Fx), Cy = 2 / (H Fy) with Fx, Fy the projection's scales.
    float cx = 2.0 * tanHalfFovY() * viewport.x * viewport.w * viewport.z;
    float cy = 2.0 * tanHalfFovY() * viewport.w;
    float cx2 = cx * cx, cy2 = cy * cy;
    float d = cy2 * zx * zx + cx2 * zy * zy + cx2 * cy2 * z * z;
    float dDx = 2.0 * (cy2 * zx * zxx + cx2 * zy * zxy + cx2 * cy2 * z * zx);
    float dDy = 2.0 * (cy2 * zx * zxy + cx2 * zy * zyy + cx2 * cy2 * z * zy);
    float ex = 0.5 * zx * dDx - zxx * d;
    float ey = 0.5 * zy * dDy - zyy * d;
    float h = (cy * ex + cx * ey) / (2.0 * d * sqrt(d));
    outSurface.x = z - uTimeStep * (cx + cy) * z * h;
}
