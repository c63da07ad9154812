// Material textures, sampled exactly as core::Texture::sample (core/texture.cpp) does: texel
// centres at (i + 0.5) / size, bilinear, u repeats, v clamps to the edge, image row 0 = v = 1.
// Textures of any size live in one buffer of RGB texels, so a per-pixel material
// index can pick any of them (sampler arrays would need a uniform index).
#include "convert.glsl"

// RGB texels of every texture, row-major, row 0 first (a buffer texture: on llvmpipe a
// texelFetch gathers several times faster than a storage-buffer load).
layout(binding = 7) uniform samplerBuffer uTexels;

struct MaterialRecord {
    ivec4 diffuse;     // x: first texel in uTexels, y: width, z: height
    ivec4 specular;
    ivec4 emission;
    ivec4 cityLights;
    vec4 params;       // x: shininess
};

layout(std430, binding = 2) readonly buffer Materials {
    MaterialRecord materials[];
};

vec3 texel(ivec4 t, int x, int y) {
    return texelFetch(uTexels, t.x + y * t.y + x).rgb;
}

vec3 sampleTexture(ivec4 t, vec2 uv) {
    int w = t.y, h = t.z;
    if (w == 1 && h == 1) return texel(t, 0, 0);
    float x = uv.x * float(w) - 0.5;
    float y = (1.0 - uv.y) * float(h) - 0.5;
    float fx0 = floor(x), fy0 = floor(y);
    float tx = x - fx0, ty = y - fy0;
    int x0 = clampToInt(mod(fx0, float(w)), 0, w - 1);
    int x1 = x0 + 1 == w ? 0 : x0 + 1;
    int y0 = clampToInt(fy0, 0, h - 1);
    int y1 = clampToInt(fy0 + 1.0, 0, h - 1);
    vec3 t00 = texel(t, x0, y0), t10 = texel(t, x1, y0);
    vec3 t01 = texel(t, x0, y1), t11 = texel(t, x1, y1);
    vec3 a = t00 + (t10 - t00) * tx;
    vec3 b = t01 + (t11 - t01) * tx;
    return a + (b - a) * ty;
}
