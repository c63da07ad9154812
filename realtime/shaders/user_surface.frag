// A user's surface filter (realtime.surface.shader = PATH): the file is included below and
// must define
//     void filterSurface(ivec2 pixel, inout SurfaceSample s);
// called once per covered pixel per pass (realtime.surface.shader_passes; each pass reads the
// previous one's result). `s` holds the pixel's values; what the function leaves in it is
// written. It may read any pixel through surface_common.glsl: depthAt, bodyAt, coveredAt,
// radiusPxAt, particleRadiusAt, normalAt, uvAt, emissionAt, eyePosition, normalFromDepth,
// and common.glsl's camera: cameraNear(), cameraFar(), tanHalfFovY(), viewport (width,
// height, 1/width, 1/height), viewFromWorld, pixelsPerUnitAt(z). Values left unchanged are
// copied bit for bit. With realtime.surface.shader_normals the normals are rebuilt from the
// final depth afterwards. Background pixels are never passed to it.
#include "common.glsl"
#include "surface_common.glsl"

struct SurfaceSample {
    float depth;      // eye depth, scene units
    vec3 normal;      // world normal, unit
    vec2 uv;          // texture coordinates
    vec3 emission;    // emitted radiance, linear
    float body;       // body id (read only)
    float radiusPx;   // the drawn particle's projected radius, pixels (read only)
};

#include "user_surface.glsl"

layout(location = 0) out vec4 outSurface;
layout(location = 1) out vec4 outNormalUv;
layout(location = 2) out vec4 outEmission;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 s = texelFetch(uSurface, p, 0);
    vec4 a = texelFetch(uNormalUv, p, 0);
    vec4 e = texelFetch(uEmission, p, 0);
    outSurface = s;
    outNormalUv = a;
    outEmission = e;
    if (s.y < 0.0) return;
    SurfaceSample given = SurfaceSample(s.x, octDecode(a.xy), a.zw, e.rgb, s.y, s.z);
    SurfaceSample x = given;
    filterSurface(p, x);
    if (x.depth != given.depth) outSurface.x = x.depth;
    if (x.normal != given.normal) outNormalUv.xy = octEncode(normalize(x.normal));
    if (x.uv != given.uv) outNormalUv.zw = x.uv;
    if (x.emission != given.emission) outEmission.rgb = x.emission;
}
