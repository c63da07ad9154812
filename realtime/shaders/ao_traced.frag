// Ambient occlusion traced in world space (realtime.ao.method = "traced"; realtime/ao_traced.h):
// the open fraction of each covered pixel's hemisphere within uRadius, the share of uRays
// cosine-weighted rays from its surface point that meet no particle sphere within uRadius, as
// the reference traces it against the implicit surface (raymarch/ao_hemisphere.h).
//  - Directions: Malley's method, as the reference's: a grid of strata on the unit square (rows
//    in s = r^2, as many as sqrt(uRays) allows, the rays shared among them) mapped onto the
//    disc and lifted onto the hemisphere; per pixel the noise (ao_noise.glsl) turns every
//    stratum's angle and moves every ray within its row. Each ray counts by its stratum's
//    area, so a count that the rows do not divide is still cosine-weighted.
//  - Self-intersection: the surface point lies on or inside the spheres it was drawn from, and
//    on a filtered depth below their bumps. The origin moves along the normal out of
//    the spheres it lies in (at most uMaxLift impostor radii, the pixel's, surface channel z),
//    then uBias impostor radii further, and spheres that still contain it are not occluders.
//  - The walk: each segment is clipped to the grid's box, then steps from cell to cell
//    (Amanatides & Woo 1987), testing the spheres each lists, until one is hit or the segment
//    ends.
#include "common.glsl"
#include "ao_noise.glsl"

layout(binding = 0) uniform sampler2D uNormalUv;  // octahedral normal, u, v
layout(binding = 2) uniform sampler2D uSurface;   // eye depth, body, radius px, material
layout(std430, binding = 5) readonly buffer OcclusionCellStart {
    uint cellStart[];  // cells + 1: each cell's first item
};
layout(std430, binding = 6) readonly buffer OcclusionItems {
    uint items[];  // sphere indices, cell by cell
};
layout(std430, binding = 7) readonly buffer OcclusionSpheres {
    vec4 spheres[];  // camera-relative centre, radius
};
uniform float uRadius;         // scene units; 0: no occlusion
uniform int uRays;             // rays per pixel
uniform float uBias;           // the origin's offset along the normal, impostor radii
uniform float uMaxLift;        // the most the origin moves out of the spheres, impostor radii
uniform vec4 uGridOriginSide;  // the grid's low corner (camera-relative), a cell's side
uniform vec3 uGridCells;       // cells per axis

layout(location = 0) out vec4 outOpen;

const float PI = 3.14159265358979;

// Whether the segment origin + t dir, t in [0, reach] (dir unit), meets the sphere s from
// outside it. A sphere containing the origin is not an occluder.
bool meets(vec3 origin, vec3 dir, float reach, vec4 s) {
    vec3 f = s.xyz - origin;
    float c = dot(f, f) - s.w * s.w;
    float b = dot(f, dir);
    if (c <= 0.0 || b <= 0.0) return false;
    float disc = b * b - c;
    return disc >= 0.0 && b - sqrt(disc) <= reach;
}

// The cell of the grid that holds x, or -1 outside it.
int cellAt(vec3 x) {
    ivec3 cells = ivec3(uGridCells);
    vec3 g = floor((x - uGridOriginSide.xyz) / uGridOriginSide.w);
    if (any(lessThan(g, vec3(0.0))) || any(greaterThanEqual(g, vec3(cells)))) return -1;
    ivec3 c = ivec3(g);
    return c.x + cells.x * (c.y + cells.y * c.z);
}

// How far along `normal` x must move to leave the spheres it lies in (and those it then lies
// in, a few rounds), at most `most`.
float liftOut(vec3 x, vec3 normal, float most) {
    float t = 0.0;
    for (int k = 0; k < 4; ++k) {
        vec3 q = x + normal * t;
        int c = cellAt(q);
        if (c < 0) break;
        float exit = t;
        for (uint i = cellStart[c]; i < cellStart[c + 1]; ++i) {
            vec4 s = spheres[items[i]];
            vec3 f = q - s.xyz;
            float inside = dot(f, f) - s.w * s.w, b = dot(f, normal);
            if (inside < 0.0) exit = max(exit, t - b + sqrt(b * b - inside));
        }
        if (exit <= t) break;
        t = min(exit, most);
        if (t >= most) break;
    }
    return t;
}

// Whether the segment meets any sphere: the cells it crosses, in order.
bool blocked(vec3 origin, vec3 dir, float reach) {
    vec3 lo = uGridOriginSide.xyz;
    float side = uGridOriginSide.w;
    ivec3 cells = ivec3(uGridCells);
    // No component exactly 0: its reciprocal large and finite, the slab tests below defined.
    vec3 d = mix(dir, vec3(1e-20), lessThan(abs(dir), vec3(1e-20)));
    vec3 inv = 1.0 / d;
    vec3 t0 = (lo - origin) * inv, t1 = (lo + vec3(cells) * side - origin) * inv;
    vec3 near = min(t0, t1), far = max(t0, t1);
    float enter = max(max(near.x, near.y), max(near.z, 0.0));
    float leave = min(min(far.x, far.y), min(far.z, reach));
    if (enter > leave) return false;
    ivec3 cell = clamp(ivec3(floor((origin + dir * enter - lo) / side)), ivec3(0), cells - 1);
    ivec3 step = ivec3(greaterThan(d, vec3(0.0))) * 2 - 1;
    vec3 delta = abs(side * inv);
    // The distance along the ray to each axis's next cell face.
    vec3 next = (lo + (vec3(cell) + vec3(greaterThan(d, vec3(0.0)))) * side - origin) * inv;
    for (int k = 0; k < cells.x + cells.y + cells.z; ++k) {
        int c = cell.x + cells.x * (cell.y + cells.y * cell.z);
        for (uint i = cellStart[c]; i < cellStart[c + 1]; ++i)
            if (meets(origin, dir, reach, spheres[items[i]])) return true;
        // The axis whose face comes first.
        int axis = next.x < next.y ? (next.x < next.z ? 0 : 2) : (next.y < next.z ? 1 : 2);
        if (next[axis] > leave) return false;
        cell[axis] += step[axis];
        if (cell[axis] < 0 || cell[axis] >= cells[axis]) return false;
        next[axis] += delta[axis];
    }
    return false;
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 s = texelFetch(uSurface, p, 0);
    if (s.y < 0.0 || uRadius <= 0.0) {
        outOpen = vec4(1.0);
        return;
    }
    vec3 normal = octDecode(texelFetch(uNormalUv, p, 0).xy);
    float particleRadius = s.z / pixelsPerUnitAt(s.x);
    vec3 position = surfacePosition(gl_FragCoord.xy, s.x);
    float lift = liftOut(position, normal, uMaxLift * particleRadius);
    vec3 origin = position + normal * (lift + uBias * particleRadius);
    // A frame about the normal (Frisvad's, with the branch of Duff et al. 2017, as the
    // reference's).
    float sgn = normal.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sgn + normal.z), b = normal.x * normal.y * a;
    vec3 u = vec3(1.0 + sgn * normal.x * normal.x * a, sgn * b, -sgn * normal.x);
    vec3 v = vec3(b, sgn + normal.y * normal.y * a, -normal.y);
    vec2 xi = noise(p);
    int rows = max(int(floor(sqrt(float(uRays)))), 1);
    float open = 0.0;
    for (int row = 0; row < rows; ++row) {
        // The rays of this row: [first, end) of 0..uRays-1.
        int first = (row * uRays + rows - 1) / rows, end = ((row + 1) * uRays + rows - 1) / rows;
        int count = end - first;
        float sr = (float(row) + xi.y) / float(rows);
        float r = sqrt(sr), z = sqrt(max(1.0 - sr, 0.0));
        for (int j = 0; j < count; ++j) {
            float phi = 2.0 * PI * fract((float(j) + 0.5) / float(count) + xi.x);
            vec3 dir = normalize(z * normal + r * (cos(phi) * u + sin(phi) * v));
            if (!blocked(origin, dir, uRadius)) open += 1.0 / (float(rows) * float(count));
        }
    }
    outOpen = vec4(open);
}
