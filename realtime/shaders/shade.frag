// The shading pass: core's shading model on the smoothed buffers, with the light's visibility
// from the shadow map (SHADOWS_MAP, SHADOWS_PCF), a filtered map (SHADOWS_ESM with ESM_SEED or
// not, SHADOWS_VSM, SHADOWS_EVSM), the occlusion spheres (SHADOWS_SPHERES) or none. Output:
// linear beauty and the visibility (the shadow AOV). VISIBILITY_TEXTURE: the visibility read
// per pixel instead (the error split). AMBIENT_OCCLUSION: the ambient term times the ambient
// occlusion pass's open fraction. EMISSIVE_LIGHT: the emissive pass's irradiance from emitting
// surfaces, lighting the albedo (light.emissive_light).
#include "common.glsl"
#include "textures.glsl"
#include "shading.glsl"
#include "convert.glsl"
#if defined(SHADOWS_ESM) || defined(SHADOWS_VSM) || defined(SHADOWS_EVSM)
#define SHADOWS_FILTERED
#include "shadow_filters.glsl"
#endif

layout(binding = 0) uniform sampler2D uNormalUv;  // octahedral normal, u, v
layout(binding = 1) uniform sampler2D uEmission;
layout(binding = 2) uniform sampler2D uSurface;
// Linear light depth in [0, 1]; SHADOWS_FILTERED: the filtered map, linear filtering;
// VISIBILITY_TEXTURE: the visibility itself per pixel (the error split's reference light).
layout(binding = 3) uniform sampler2D uShadowMap;
#ifdef AMBIENT_OCCLUSION
layout(binding = 4) uniform sampler2D uAmbientOcclusion;  // the open fraction (ao.frag)
#endif
#ifdef EMISSIVE_LIGHT
layout(binding = 5) uniform sampler2D uIrradiance;  // E from emitting surfaces (rgb, linear)
#endif

#ifdef SHADOWS_SPHERES
const int MAX_SPHERES = 20;  // bodies over 5 % of the particles: at most 19
uniform int uSphereCount;
uniform vec4 uSpheres[MAX_SPHERES];  // camera-relative centre, radius
uniform float uSphereBodies[MAX_SPHERES];
#endif

layout(location = 0) out vec4 outBeautyShadow;

// Cap of tan(angle between the normal and the light) in the slope bias.
const float MAX_SLOPE = 10.0;
// PCF with a sun of some angular radius: the blocker search and the filter reach at most this
// many texels (a 33 x 33 grid).
const float MAX_PCF_RADIUS = 16.0;
const int MAX_PCF_TAPS = 16;  // ceil(MAX_PCF_RADIUS)

#if defined(SHADOWS_PCF)
// Percentage-closer filtering over a disc of `radius` texels: taps on a grid of one texel.
float pcf(ivec2 centre, ivec2 size, float radius, float depth) {
    int n = clampToInt(ceil(radius), 0, MAX_PCF_TAPS);  // a NaN radius: the centre's texel
    float lit = 0.0, count = 0.0;
    for (int j = -n; j <= n; ++j) {
        for (int i = -n; i <= n; ++i) {
            if (float(i * i + j * j) > radius * radius + 1e-3) continue;
            ivec2 q = clamp(centre + ivec2(i, j), ivec2(0), size - 1);
            lit += texelFetch(uShadowMap, q, 0).r >= depth ? 1.0 : 0.0;
            count += 1.0;
        }
    }
    return lit / count;
}

// The filter radius of PCF in texels: shadow_map.pcf_radius, widened under a sun of angular
// radius atan(shadowBias.w) to the penumbra that the mean blocker in the search disc casts
// (percentage-closer soft shadows, Fernando 2005): (receiver - blocker depth) tan(radius).
float pcfRadius(ivec2 centre, ivec2 size, float depth) {
    float tanSun = shadowBias.w;
    if (tanSun <= 0.0) return shadowBias.z;
    float range = shadowRange.y - shadowRange.x;  // scene units per unit of map depth
    float search = min(depth * range * tanSun / shadowRange.z, MAX_PCF_RADIUS);
    int n = clampToInt(ceil(search), 0, MAX_PCF_TAPS);
    float sum = 0.0, count = 0.0;
    for (int j = -n; j <= n; ++j) {
        for (int i = -n; i <= n; ++i) {
            if (float(i * i + j * j) > search * search + 1e-3) continue;
            float d = texelFetch(uShadowMap, clamp(centre + ivec2(i, j), ivec2(0), size - 1), 0).r;
            if (d < depth) {
                sum += d;
                count += 1.0;
            }
        }
    }
    if (count == 0.0) return shadowBias.z;
    float penumbra = (depth - sum / count) * range * tanSun / shadowRange.z;
    return clamp(max(penumbra, shadowBias.z), 0.0, MAX_PCF_RADIUS);
}
#endif

float visibility(vec3 position, vec3 normal, float body, float worldRadius) {
#if defined(VISIBILITY_TEXTURE)
    return texelFetch(uShadowMap, ivec2(gl_FragCoord.xy), 0).r;
#elif defined(SHADOWS_MAP) || defined(SHADOWS_PCF) || defined(SHADOWS_FILTERED)
    vec3 l = (lightView * vec4(position, 1.0)).xyz;
    vec2 tc = (lightClip * vec4(l, 1.0)).xy * 0.5 + 0.5;
    // Outside the map, or NaN (which fails every comparison), is lit.
    if (!(all(greaterThanEqual(tc, vec2(0.0))) && all(lessThanEqual(tc, vec2(1.0))))) return 1.0;
    // Slope-scaled bias in units of the larger of the particle radius and the shadow texel:
    // the impostor surface is bumpy on the scale of a particle, the map on that of a texel.
    float cosine = clamp(dot(normal, -light.xyz), 1e-3, 1.0);
    float slope = min(sqrt(1.0 - cosine * cosine) / cosine, MAX_SLOPE);
    float unit = max(worldRadius, shadowRange.z);
    float bias = (shadowBias.x + shadowBias.y * slope) * unit;
    float depth = (-l.z - bias - shadowRange.x) / (shadowRange.y - shadowRange.x);
#if defined(SHADOWS_FILTERED)
    return filteredVisibility(uShadowMap, tc, depth);
#else
    ivec2 size = textureSize(uShadowMap, 0);
    vec2 texelPos = tc * vec2(size);
#if defined(SHADOWS_PCF)
    ivec2 centre = saturateToInt(floor(texelPos));
    return pcf(centre, size, pcfRadius(centre, size, depth), depth);
#else
    ivec2 q = clamp(saturateToInt(floor(texelPos)), ivec2(0), size - 1);
    return texelFetch(uShadowMap, q, 0).r >= depth ? 1.0 : 0.0;
#endif
#endif
#elif defined(SHADOWS_SPHERES)
    // A ray towards the sun; a sphere of another body ahead of the point occludes it.
    vec3 dir = -light.xyz;
    for (int i = 0; i < uSphereCount; ++i) {
        if (uSphereBodies[i] == body) continue;
        vec3 oc = position - uSpheres[i].xyz;
        float b = dot(oc, dir);
        float c = dot(oc, oc) - uSpheres[i].w * uSpheres[i].w;
        float disc = b * b - c;
        if (disc < 0.0) continue;
        float tFar = -b + sqrt(disc);
        if (tFar > 0.0) return 0.0;
    }
    return 1.0;
#else
    return 1.0;
#endif
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 s = texelFetch(uSurface, p, 0);
    if (s.y < 0.0) {
        outBeautyShadow = vec4(0.0);
        return;
    }
    vec4 a = texelFetch(uNormalUv, p, 0);
#ifdef EMISSION
    vec3 emission = texelFetch(uEmission, p, 0).rgb;
#else
    const vec3 emission = vec3(0.0);  // nothing in the scene emits
#endif
    float z = s.x;
    vec3 position = surfacePosition(gl_FragCoord.xy, z);
    vec3 normal = octDecode(a.xy);
    float worldRadius = s.z / pixelsPerUnitAt(z);
    // A surface facing away from the light is shadowed by its own body (what a shadow ray
    // from the surface finds); the beauty does not change, as it lights only n.l > 0.
    float vis =
        dot(normal, -light.xyz) > 0.0 ? visibility(position, normal, s.y, worldRadius) : 0.0;
#ifdef AMBIENT_OCCLUSION
    float open = min(texelFetch(uAmbientOcclusion, p, 0).r, 1.0);  // gtao's may pass 1 (ao.frag)
#else
    const float open = 1.0;
#endif
#ifdef EMISSIVE_LIGHT
    vec3 irradiance = texelFetch(uIrradiance, p, 0).rgb;
#else
    const vec3 irradiance = vec3(0.0);  // no light from emitting surfaces
#endif
    vec3 color = shadeSurface(int(toIndex(s.w)), normal, -normalize(position), a.zw, emission,
                              vis, open, irradiance);
    outBeautyShadow = vec4(color, vis);
}
