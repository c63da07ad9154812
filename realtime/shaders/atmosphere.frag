// The atmosphere pass (realtime/atmosphere_pass.cpp): every pixel's view ray through a body's
// atmosphere (atmosphere.glsl) up to its end point, chosen by the variant: END_IMPOSTOR (the
// G-buffer's impostor depth), END_FILTERED (the depth the shade pass read), END_SPHERE (the
// analytic inner sphere; another body's pixels keep the filtered depth) or END_BLEND (the
// filtered depth nearer than uBlend.x, the sphere beyond uBlend.y, mixed by distance between).
// Out: the beauty times the transmittance plus the in-scatter (a: the light's visibility, kept),
// and the in-scatter alone.
#include "common.glsl"
#include "atmosphere.glsl"

layout(binding = 0) uniform sampler2D uBeauty;    // linear rgb, visibility
layout(binding = 1) uniform sampler2D uImpostor;  // the G-buffer's eye depth, body, -, -
layout(binding = 2) uniform sampler2D uFiltered;  // the shade pass's eye depth, body, -, -

uniform vec3 uCentre;  // the shell's centre, camera-relative
uniform float uBody;   // the atmosphere's body id
uniform vec2 uBlend;   // END_BLEND: near, far (scene units from the camera)

layout(location = 0) out vec4 outBeauty;
layout(location = 1) out vec4 outInscatter;

// The distance along the view ray (`scale`: its length per unit of eye depth) of a surface
// texel's depth; ATMOSPHERE_NO_END on the background.
float depthEnd(vec4 surface, float scale) {
    return surface.y < 0.0 ? ATMOSPHERE_NO_END : surface.x * scale;
}

#if defined(END_BLEND)
// The depth's end point nearer than uBlend.x, the sphere's beyond uBlend.y, linear between by
// the depth's distance. Where the ray misses the sphere its end point is the shell's exit (what
// END_SPHERE integrates to), so that the mix is continuous.
float blendEnd(float depth, float sphere, vec3 origin, vec3 direction) {
    if (depth >= ATMOSPHERE_NO_END) return sphere;
    float w = clamp((depth - uBlend.x) / (uBlend.y - uBlend.x), 0.0, 1.0);
    if (w <= 0.0) return depth;
    if (w >= 1.0) return sphere;
    float t0, t1;
    if (sphere >= ATMOSPHERE_NO_END && raySphere(origin, direction, uShell.y, t0, t1)) sphere = t1;
    return mix(depth, sphere, w);
}
#endif

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 ray = surfacePosition(gl_FragCoord.xy, 1.0);
    float scale = length(ray);
    vec3 direction = ray / scale;
    vec3 origin = -uCentre;
#if defined(END_IMPOSTOR)
    float end = depthEnd(texelFetch(uImpostor, p, 0), scale);
#else
    vec4 filtered = texelFetch(uFiltered, p, 0);
    float end = depthEnd(filtered, scale);
#if defined(END_SPHERE) || defined(END_BLEND)
    if (filtered.y < 0.0 || filtered.y == uBody) {
        float sphere = sphereEntry(origin, direction, uShell.x);
#if defined(END_SPHERE)
        end = sphere;
#else
        end = blendEnd(end, sphere, origin, direction);
#endif
    }
#endif
#endif
    vec3 transmittance, inscatter;
    integrateAtmosphere(origin, direction, end, transmittance, inscatter);
    vec4 beauty = texelFetch(uBeauty, p, 0);
    outBeauty = vec4(beauty.rgb * transmittance + inscatter, beauty.a);
    outInscatter = vec4(inscatter, 0.0);
}
