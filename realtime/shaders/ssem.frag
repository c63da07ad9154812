// Screen-space emissive light (realtime/emissive_pass.cpp, emissive.method = "ssem"), after
// the screen-space emissive materials of deferred engines: from each covered pixel, rays in
// cosine-weighted directions about the normal are marched against the depth buffer; the first
// sample that lies behind it by less than the thickness meets the surface there, and that
// pixel's (smoothed) emission is the radiance the ray brings. With cosine-weighted directions
// each ray carries L cos(theta) d(omega) / pdf = pi L / N, so E = pi / N sum L. A ray that
// leaves the image or meets nothing brings 0: an emitter off screen, or hidden behind a
// nearer surface, lights nothing (what the reference, tracing the scene, does not miss).
// With EMITTER_TARGET ("ssem_target") the rays are marched in the emitter target's projection
// instead: the emitting bodies alone, drawn from the camera with a wider field of view
// (emissive_pass.cpp), so that an emitter beside the view still lights what is in view; a ray
// then passes through every surface that does not emit (no shadowing).
// Output: E (rgb, linear).
#include "common.glsl"
#include "convert.glsl"

layout(binding = 0) uniform sampler2D uNormalUv;  // octahedral normal, u, v
layout(binding = 1) uniform sampler2D uEmission;  // emitted radiance (rgb)
layout(binding = 2) uniform sampler2D uSurface;   // eye depth, body, radius px, material
uniform int uDirections;   // rays per pixel
uniform int uSteps;        // samples along each
uniform float uMaxPixels;  // a ray's reach on screen, pixels
uniform float uThickness;  // particle radii
#if defined(EMITTER_TARGET)
layout(binding = 3) uniform sampler2D uTargetSurface;   // the emitters' surface, as uSurface
layout(binding = 4) uniform sampler2D uTargetEmission;  // the emitters' radiance (rgb)
uniform vec2 uTargetTan;   // the target's tan(fov / 2), horizontal and vertical
uniform vec2 uTargetSize;  // the target's pixels
#endif

layout(location = 0) out vec4 outIrradiance;

const float PI = 3.14159265358979;

// Interleaved gradient noise (Jimenez 2014), two values per pixel: the directions' turn and
// the steps' jitter.
vec2 noise(ivec2 p) {
    vec2 q = vec2(p);
    float a = fract(52.9829189 * fract(dot(q, vec2(0.06711056, 0.00583715))));
    float b = fract(52.9829189 * fract(dot(q + vec2(5.588238), vec2(0.06711056, 0.00583715))));
    return vec2(a, b);
}

// Pixel (window coordinates) and eye depth of a camera-relative point in front of the camera.
vec3 project(vec3 position) {
    vec3 eye = mat3(viewFromWorld) * position;
    float z = -eye.z;
#if defined(EMITTER_TARGET)
    // In the emitter target's pixels.
    return vec3((eye.xy / (z * uTargetTan) * 0.5 + 0.5) * uTargetSize, z);
#endif
    float aspect = viewport.x * viewport.w;
    vec2 ndc = vec2(eye.x / (z * camera.z * aspect), eye.y / (z * camera.z));
    return vec3((ndc * 0.5 + 0.5) * viewport.xy, z);
}

// The radiance the ray from `position` along `dir` brings: the emission of the first pixel
// whose surface it meets, 0 when it leaves the image or meets nothing within its reach, or
// meets the receiver's own body (a convex body does not light itself; its impostors' bumps
// would).
vec3 march(vec3 position, vec3 dir, float body, float reach, float jitter) {
    // Cut at the near plane (a ray toward the camera) and at uMaxPixels on screen.
    float towardCamera = (mat3(viewFromWorld) * dir).z;  // the eye depth falls by this per unit
    vec3 start = project(position);
    if (towardCamera > 0.0)
        reach = min(reach, 0.99 * (start.z - cameraNear()) / towardCamera);
    vec3 end = project(position + dir * reach);
    float pixels = length(end.xy - start.xy);
    if (pixels < 1.0) return vec3(0.0);  // along the view ray: nothing on screen to meet
    float span = min(pixels, uMaxPixels);
#if defined(EMITTER_TARGET)
    ivec2 size = ivec2(uTargetSize);
#else
    ivec2 size = ivec2(viewport.xy);
#endif
    for (int j = 0; j < uSteps; ++j) {
        // From a pixel off the receiver to the ray's reach on screen; the eye depth of the ray
        // there by perspective-correct interpolation of 1 / z.
        float f = (1.0 + (float(j) + jitter) / float(uSteps) * (span - 1.0)) / pixels;
        ivec2 q = saturateToInt(floor(mix(start.xy, end.xy, f)));
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) return vec3(0.0);
        float z = 1.0 / mix(1.0 / start.z, 1.0 / end.z, f);
#if defined(EMITTER_TARGET)
        vec4 s = texelFetch(uTargetSurface, q, 0);
        if (s.y < 0.0) continue;
        float behind = z - s.x;
        // The radius in the target's pixels, and the target's pixels per unit at that depth.
        if (behind > 0.0 && behind < uThickness * s.z * uTargetTan.y * s.x * 2.0 / uTargetSize.y)
            return s.y == body ? vec3(0.0) : texelFetch(uTargetEmission, q, 0).rgb;
#else
        vec4 s = texelFetch(uSurface, q, 0);
        if (s.y < 0.0) continue;
        float behind = z - s.x;
        if (behind > 0.0 && behind < uThickness * s.z / pixelsPerUnitAt(s.x))
            return s.y == body ? vec3(0.0) : texelFetch(uEmission, q, 0).rgb;
#endif
    }
    return vec3(0.0);
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 s = texelFetch(uSurface, p, 0);
    if (s.y < 0.0) {
        outIrradiance = vec4(0.0);
        return;
    }
    vec3 position = surfacePosition(gl_FragCoord.xy, s.x);
    vec3 normal = octDecode(texelFetch(uNormalUv, p, 0).xy);
    vec3 t = normalize(abs(normal.z) < 0.9 ? cross(normal, vec3(0.0, 0.0, 1.0))
                                           : cross(normal, vec3(1.0, 0.0, 0.0)));
    vec3 b = cross(normal, t);
    vec2 xi = noise(p);
    // The world length that spans uMaxPixels at the receiver's depth.
    float reach = uMaxPixels / pixelsPerUnitAt(s.x);
    vec3 sum = vec3(0.0);
    for (int k = 0; k < uDirections; ++k) {
        // Cosine-weighted (Malley: the unit disc, stratified in radius and turned by the golden
        // angle and the pixel's noise, lifted onto the hemisphere).
        float u = (float(k) + 0.5) / float(uDirections);
        float phi = 2.0 * PI * fract(float(k) * 0.61803398875 + xi.x);
        float r = sqrt(u);
        vec3 dir = t * (r * cos(phi)) + b * (r * sin(phi)) + normal * sqrt(max(1.0 - u, 0.0));
        sum += march(position, dir, s.y, reach, xi.y);
    }
    outIrradiance = vec4(PI / float(uDirections) * sum, 0.0);
}
