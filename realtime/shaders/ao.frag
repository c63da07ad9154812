// Screen-space ambient occlusion (realtime/ao_pass.cpp): the open fraction of each covered
// pixel's hemisphere within uRadius (light.ao_radius, scene units), from the depth and normals
// the shade pass reads. The reference traces the same quantity exactly: the cosine-weighted
// share of directions that meet no surface within the radius (raymarch/ao_hemisphere.h).
//  - AO_SSAO: normal-oriented hemisphere sampling (the Crytek/StarCraft II family): points in
//    the hemisphere about the normal, cosine-distributed, occluded where the depth buffer lies
//    in front of them within the radius.
//  - AO_HBAO: horizon-based (Bavoil & Sainz 2008): per screen direction, the highest horizon
//    within the radius above the tangent plane raised by an angle bias, occlusion
//    sin(h) - sin(t), falloff 1 - r^2/R^2.
//    Its weighting is the image plane's, not the normal's cosine.
//  - AO_GTAO: ground-truth AO (Jimenez et al. 2016): per slice about the view vector, two
//    horizons clamped to the normal's hemisphere and the cosine-weighted visibility between
//    them in closed form, weighted by the projected normal's length; horizons within an angle
//    bias above the tangent plane count nothing (hbao's answer to the impostors' bumps), and
//    each higher one is lowered by it.
// Thickness (uThickness > 0): the depth buffer holds only the front of each occluder, and the
// horizons above take all that lies behind it for solid: the front of a ball hanging over a
// slab stands for a wall reaching back to the slab. With a thickness, each sample's occluder
// is a segment of uThickness particle radii along its view ray, behind what is seen (the
// thickness heuristic of XeGTAO, Intel 2021, made explicit): ssao's points behind it are open,
// hbao counts the directions between its back and its front only, and gtao marks the sectors
// between them in a bit mask per slice and integrates the cosine-weighted visibility over the
// unmarked ones (the visibility bitmask of Therrien, Levesque and Gilet 2023).
// SECOND_LAYER (realtime.ao.layers = 2): each occluder's back is read from a second depth layer,
// the back of the body seen at each pixel (gbuffer.frag's BACK_LAYER), not assumed: a layered
// depth buffer in the spirit of the deep G-buffer (Mara, McGuire, Nowrouzezahrai and Luebke
// 2016), whose second layer for particles is the body's exit, since the nearest surface behind
// the first inside a body of overlapping impostors is only the next particle. With a thickness
// as well, the nearer of the two backs.
// Noise (per pixel: slice rotation and step jitter): ao_noise.glsl.
#include "common.glsl"
#include "convert.glsl"
#include "ao_noise.glsl"

layout(binding = 0) uniform sampler2D uNormalUv;  // octahedral normal, u, v
layout(binding = 2) uniform sampler2D uSurface;   // eye depth, body, radius px, material
uniform float uRadius;    // scene units; 0: no occlusion
uniform int uSlices;      // screen directions (hbao, gtao), or sample rings (ssao)
uniform int uSteps;       // samples along each
uniform float uMaxPixels;  // the screen radius's cap, pixels
uniform float uAngleBias;  // hbao: radians added to the tangent's elevation
uniform float uGtaoBias;   // gtao: the same, radians
uniform float uThickness;  // each occluder's depth, particle radii; 0: without end
#ifdef SECOND_LAYER
layout(binding = 6) uniform sampler2D uBack;  // the eye depth of the body's back; 0: none
#endif

// Whether each occluder ends behind its front (a thickness or a second layer), or is a wall
// reaching back without end (the methods as published).
bool finiteOccluders() {
#ifdef SECOND_LAYER
    return true;
#else
    return uThickness > 0.0;
#endif
}

layout(location = 0) out vec4 outOpen;

const float PI = 3.14159265358979;

// The eye depth of the surface at pixel q: false on the background or off the image.
bool depthAt(ivec2 q, out float z) {
    ivec2 size = ivec2(viewport.xy);
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) return false;
    vec4 s = texelFetch(uSurface, q, 0);
    z = s.x;
    return s.y >= 0.0;
}

// The camera-relative position of the surface at pixel q, as depthAt.
bool surfaceAt(ivec2 q, out vec3 position) {
    float z;
    if (!depthAt(q, z)) return false;
    position = surfacePosition(vec2(q) + 0.5, z);
    return true;
}

// As surfaceAt, and the back of the occluder seen there: uThickness particle radii (the
// impostor's radius at q) further along its view ray, or the second layer's back, the nearer
// of the two where both are set. Where the second layer holds no back behind the front (no
// impostor of that body behind a filtered depth), the impostor's own diameter.
bool occluderAt(ivec2 q, out vec3 front, out vec3 back) {
    ivec2 size = ivec2(viewport.xy);
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) return false;
    vec4 s = texelFetch(uSurface, q, 0);
    if (s.y < 0.0) return false;
    front = surfacePosition(vec2(q) + 0.5, s.x);
    float radius = s.z / pixelsPerUnitAt(s.x);
    float depth = uThickness > 0.0 ? uThickness * radius : 1e30;
#ifdef SECOND_LAYER
    float behind = texelFetch(uBack, q, 0).x - s.x;
    depth = min(depth, behind > 0.0 ? behind * length(front) / s.x : 2.0 * radius);
#endif
    back = front * (1.0 + depth / max(length(front), 1e-20));
    return true;
}

// The part [t0, t1] (t1 < t0: none) of the segment a + t (b - a), t in [0, 1], within the
// radius of `centre`.
vec2 withinRadius(vec3 a, vec3 b, vec3 centre) {
    vec3 d = b - a, f = a - centre;
    float dd = dot(d, d), fd = dot(f, d), c = dot(f, f) - uRadius * uRadius;
    if (dd <= 0.0) return c <= 0.0 ? vec2(0.0, 1.0) : vec2(1.0, 0.0);
    float disc = fd * fd - dd * c;
    if (disc < 0.0) return vec2(1.0, 0.0);
    float root = sqrt(disc);
    return vec2(max((-fd - root) / dd, 0.0), min((-fd + root) / dd, 1.0));
}

// Eye depth and pixel (window coordinates) of a camera-relative point.
vec3 project(vec3 position) {
    vec3 eye = mat3(viewFromWorld) * position;
    float z = -eye.z;
    float aspect = viewport.x * viewport.w;
    vec2 ndc = vec2(eye.x / (z * camera.z * aspect), eye.y / (z * camera.z));
    return vec3((ndc * 0.5 + 0.5) * viewport.xy, z);
}

// The slice's direction on screen (unit) and in the world, at right angles to the view vector.
void sliceDirection(float angle, vec3 toEye, out vec2 screen, out vec3 world) {
    screen = vec2(cos(angle), sin(angle));
    vec3 d = transpose(mat3(viewFromWorld)) * vec3(screen, 0.0);
    world = normalize(d - toEye * dot(d, toEye));
}

#if defined(AO_SSAO)
// The eye depth of the back of the occluder seen at pixel q at eye depth z (occluderAt).
float behind(ivec2 q, float z) {
    vec3 front, back;
    if (!occluderAt(q, front, back)) return z;
    return z * length(back) / max(length(front), 1e-20);
}

float openFraction(ivec2 p, vec3 position, vec3 normal, vec3 toEye, float pixels, vec2 xi) {
    // A frame about the normal.
    vec3 t = normalize(abs(normal.z) < 0.9 ? cross(normal, vec3(0.0, 0.0, 1.0))
                                           : cross(normal, vec3(1.0, 0.0, 0.0)));
    vec3 b = cross(normal, t);
    int samples = uSlices * uSteps;
    float closed = 0.0;
    for (int k = 0; k < samples; ++k) {
        // Cosine-distributed directions (Malley: the disc lifted), stratified in radius,
        // turned by the golden angle and the pixel's noise; distances spread over the radius
        // with more of them near the point.
        float u = (float(k) + 0.5) / float(samples);
        float phi = 2.0 * PI * fract(float(k) * 0.61803398875 + xi.x);
        float r = sqrt(u);
        vec3 dir = t * (r * cos(phi)) + b * (r * sin(phi)) + normal * sqrt(max(1.0 - u, 0.0));
        float f = fract(float(k) * 0.7548776662 + xi.y);
        float reach = uRadius * mix(0.1, 1.0, f * f);
        vec3 q = position + dir * reach;
        vec3 screen = project(q);
        float zSeen;
        if (!depthAt(saturateToInt(floor(screen.xy)), zSeen)) continue;
        // The depth buffer in front of the point, by less than the radius (the range check),
        // and with a thickness, the point not behind the occluder's back.
        float bias = 0.02 * uRadius;
        if (zSeen < screen.z - bias && screen.z - zSeen < uRadius &&
            (!finiteOccluders() || screen.z < behind(saturateToInt(floor(screen.xy)), zSeen)))
            closed += 1.0;
    }
    return 1.0 - closed / float(samples);
}
#elif defined(AO_HBAO)
float openFraction(ivec2 p, vec3 position, vec3 normal, vec3 toEye, float pixels, vec2 xi) {
    float closed = 0.0;
    for (int i = 0; i < uSlices; ++i) {
        vec2 screen;
        vec3 world;
        sliceDirection(2.0 * PI * (float(i) + xi.x) / float(uSlices), toEye, screen, world);
        // The tangent's elevation above the image plane along this direction.
        float nd = dot(normal, world), nv = dot(normal, toEye);
        // Raised by the angle bias (the paper's answer to a coarse surface: samples just above
        // the tangent plane, here the impostors' bumps under a smooth normal, count nothing).
        float sinT = sin(min(asin(clamp(-nd / max(sqrt(nd * nd + nv * nv), 1e-6), -1.0, 1.0)) +
                                 uAngleBias,
                             0.5 * PI));
        float sinH = sinT, occlusion = 0.0;
        for (int j = 0; j < uSteps; ++j) {
            float along = (float(j) + xi.y) / float(uSteps) * pixels + 1.0;
            vec3 q, back;
            if (!occluderAt(saturateToInt(floor(vec2(p) + 0.5 + screen * along)), q, back))
                continue;
            vec3 v = q - position;
            float r2 = dot(v, v);
            if (r2 > uRadius * uRadius || r2 <= 0.0) continue;
            float s = dot(v, toEye) * inversesqrt(r2);
            if (s > sinH) {
                // With a thickness, the directions below the occluder's back are not its.
                vec3 b = back - position;
                float from = finiteOccluders() ? max(dot(b, toEye) / length(b), sinH) : sinH;
                occlusion += (1.0 - r2 / (uRadius * uRadius)) * max(s - from, 0.0);
                sinH = s;
            }
        }
        closed += occlusion;
    }
    return clamp(1.0 - closed / float(uSlices), 0.0, 1.0);
}
#else  // AO_GTAO
// The cosine-weighted visibility between the horizons h1 <= n <= h2 of a slice whose projected
// normal makes the angle n with the view vector (Jimenez et al. 2016, eq. 10).
float sliceVisibility(float h1, float h2, float n) {
    float cn = cos(n), sn = sin(n);
    return 0.25 * (-cos(2.0 * h1 - n) + cn + 2.0 * h1 * sn) +
           0.25 * (-cos(2.0 * h2 - n) + cn + 2.0 * h2 * sn);
}

// The cosine-weighted visibility of the slice between the view vector and the angle h, signed
// (negative for h < 0): sliceVisibility(h1, h2, n) = visibleUpTo(h2, n) - visibleUpTo(h1, n).
float visibleUpTo(float h, float n) {
    return sign(h) * 0.25 * (-cos(2.0 * h - n) + cos(n) + 2.0 * h * sin(n));
}

// The sectors of a slice's bit mask: SECTORS equal angles over the normal's half-circle.
const int SECTORS = 32;

// The signed angle from the view vector of the point x seen from `position`, on the side
// `way` (1: along the slice direction, -1: against it).
float angleTo(vec3 x, vec3 position, vec3 toEye, float way) {
    vec3 v = x - position;
    return way * acos(clamp(dot(v, toEye) / max(length(v), 1e-20), -1.0, 1.0));
}

// The bits of the sectors whose centres lie in [a, b] (angles, lo the first sector's start).
uint sectorBits(float a, float b, float lo) {
    const float width = PI / float(SECTORS);
    int first = max(int(ceil((a - lo) / width - 0.5)), 0);
    int last = min(int(floor((b - lo) / width - 0.5)), SECTORS - 1);
    if (last < first) return 0u;
    int count = last - first + 1;
    return (count >= 32 ? 0xffffffffu : (1u << uint(count)) - 1u) << uint(first);
}

// One slice's visibility with finite occluders: the sectors each sample's occluder spans from
// its front to its back (clipped to the radius) marked, the open ones integrated.
float sliceVisibilityWithThickness(ivec2 p, vec3 position, vec3 toEye, vec2 screen, float n,
                                   float pixels, float jitter) {
    float lo = n - 0.5 * PI;
    uint occluded = 0u;
    for (int side = 0; side < 2; ++side) {
        float way = side == 0 ? 1.0 : -1.0;
        for (int j = 0; j < uSteps; ++j) {
            float along = (float(j) + jitter) / float(uSteps) * pixels + 1.0;
            vec3 front, back;
            ivec2 at = saturateToInt(floor(vec2(p) + 0.5 + way * screen * along));
            if (!occluderAt(at, front, back)) continue;
            vec2 t = withinRadius(front, back, position);
            if (t.y < t.x) continue;
            float a = angleTo(mix(front, back, t.x), position, toEye, way);
            float b = angleTo(mix(front, back, t.y), position, toEye, way);
            occluded |= sectorBits(min(a, b), max(a, b), lo);
        }
    }
    // Within the angle bias above the tangent plane on either side, nothing counts.
    occluded &= ~(sectorBits(lo, lo + uGtaoBias, lo) | sectorBits(lo + PI - uGtaoBias, lo + PI, lo));
    float open = 0.0, below = visibleUpTo(lo, n);
    for (int k = 0; k < SECTORS; ++k) {
        float above = visibleUpTo(lo + float(k + 1) * (PI / float(SECTORS)), n);
        if ((occluded & (1u << uint(k))) == 0u) open += above - below;
        below = above;
    }
    return open;
}

float openFraction(ivec2 p, vec3 position, vec3 normal, vec3 toEye, float pixels, vec2 xi) {
    float open = 0.0;
    for (int i = 0; i < uSlices; ++i) {
        vec2 screen;
        vec3 world;
        // Slices cover half a turn: each has two sides.
        sliceDirection(PI * (float(i) + xi.x) / float(uSlices), toEye, screen, world);
        // The normal projected into the slice (spanned by `world` and the view vector).
        vec3 axis = cross(world, toEye);
        vec3 projected = normal - axis * dot(normal, axis);
        float weight = sqrt(dot(projected, projected));
        if (weight < 1e-6) continue;
        float n = atan(dot(projected, world), dot(projected, toEye));
        if (finiteOccluders()) {
            open += weight * sliceVisibilityWithThickness(p, position, toEye, screen, n, pixels,
                                                          xi.y);
            continue;
        }
        // The horizons: the largest cosine to the view vector on each side, within the radius.
        float best[2] = float[2](-1.0, -1.0);
        for (int side = 0; side < 2; ++side) {
            float way = side == 0 ? 1.0 : -1.0;
            for (int j = 0; j < uSteps; ++j) {
                float along = (float(j) + xi.y) / float(uSteps) * pixels + 1.0;
                vec3 q;
                ivec2 at = saturateToInt(floor(vec2(p) + 0.5 + way * screen * along));
                if (!surfaceAt(at, q)) continue;
                vec3 v = q - position;
                float r2 = dot(v, v);
                if (r2 > uRadius * uRadius || r2 <= 0.0) continue;
                best[side] = max(best[side], dot(v, toEye) * inversesqrt(r2));
            }
        }
        // Lowered by the angle bias: a horizon within it above the tangent plane is none.
        float h2 = min(acos(clamp(best[0], -1.0, 1.0)) + uGtaoBias, n + 0.5 * PI);
        float h1 = max(-acos(clamp(best[1], -1.0, 1.0)) - uGtaoBias, n - 0.5 * PI);
        open += weight * sliceVisibility(h1, h2, n);
    }
    // Not capped at 1: one slice's estimate of an open surface is |n_p| (cos n + n sin n), above
    // 1 for some slice directions and below for others, and only its mean over the directions is
    // 1. Capping each pixel would darken every open surface (by 0.1 with one slice); the blur
    // averages first, and the shading caps what is left (shade.frag).
    return max(open / float(uSlices), 0.0);
}
#endif

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 s = texelFetch(uSurface, p, 0);
    if (s.y < 0.0 || uRadius <= 0.0) {
        outOpen = vec4(1.0);
        return;
    }
    vec3 position = surfacePosition(gl_FragCoord.xy, s.x);
    vec3 normal = octDecode(texelFetch(uNormalUv, p, 0).xy);
    vec3 toEye = -normalize(position);
    // The radius on screen, capped: a point near the camera would look across the image.
    float pixels = min(uRadius * pixelsPerUnitAt(s.x), uMaxPixels);
    outOpen = vec4(openFraction(p, position, normal, toEye, pixels, noise(p)));
}
