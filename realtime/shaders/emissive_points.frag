// The light of emitting surfaces as point sources (realtime/emissive_pass.cpp,
// emissive.method = "point_lights"): each emitting body a point at its centre of intensity
// I = pi R^2 L (R its surface radius, L its mean radiance), so that a receiver at distance d
// whose normal makes the angle theta with it gets E = I cos(theta) / d^2, the irradiance of a
// uniformly glowing sphere wholly above the horizon (pi L (R / d)^2 cos(theta)). Nothing
// shadows it, and a body's own surface is not lit by its own point. Output: E (rgb, linear).
#include "common.glsl"

layout(binding = 0) uniform sampler2D uNormalUv;  // octahedral normal, u, v
layout(binding = 2) uniform sampler2D uSurface;   // eye depth, body, radius px, material

const int MAX_EMITTERS = 16;  // realtime/emissive_pass.cpp: the brightest bodies
uniform int uEmitterCount;
uniform vec4 uEmitters[MAX_EMITTERS];     // camera-relative centre, surface radius R
uniform vec4 uIntensities[MAX_EMITTERS];  // I (rgb), the body's id

layout(location = 0) out vec4 outIrradiance;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 s = texelFetch(uSurface, p, 0);
    if (s.y < 0.0) {
        outIrradiance = vec4(0.0);
        return;
    }
    vec3 position = surfacePosition(gl_FragCoord.xy, s.x);
    vec3 normal = octDecode(texelFetch(uNormalUv, p, 0).xy);
    vec3 e = vec3(0.0);
    for (int i = 0; i < uEmitterCount; ++i) {
        if (uIntensities[i].w == s.y) continue;
        vec3 v = uEmitters[i].xyz - position;
        float d = length(v);
        if (d <= 0.0) continue;
        // Inside the sphere the closed form would grow without bound: d no less than R.
        float r = max(d, uEmitters[i].w);
        e += uIntensities[i].rgb * max(dot(normal, v) / d, 0.0) / (r * r);
    }
    outIrradiance = vec4(e, 0.0);
}
