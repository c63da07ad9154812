// realtime.particles.normal = "gradient", first half: each particle adds its kernel's gradient
// v_j W'(|x - x_j|) (x - x_j) / |x - x_j| at the surface point x the G-buffer holds for this
// pixel (additive blending into an RGBA32F target), so that the target ends with the colour
// field's exact gradient at x: the sum over every particle whose support covers x, as the
// raymarcher's analytic normal sums them.
#include "common.glsl"
#include "kernels.glsl"

layout(binding = 0) uniform sampler2D uSurface;  // G-buffer: eye depth (+inf background), ...

flat in int vKernel;
layout(location = 0) out vec4 outGradient;

void main() {
    float z = texelFetch(uSurface, ivec2(gl_FragCoord.xy), 0).x;
    if (isinf(z)) discard;
    Kernel k = kernels[vKernel];
    vec3 d = surfacePosition(gl_FragCoord.xy, z) - k.positionSupport.xyz;
    float r = length(d);
    float q = r * k.coefficients.y;
    if (q >= 2.0 || r == 0.0) discard;
    // M4: w'(q) = -3 q + 2.25 q^2 below 1, -0.75 (2 - q)^2 up to 2 (core/sph_kernel.h).
    float dw = q < 1.0 ? q * (2.25 * q - 3.0) : -0.75 * (2.0 - q) * (2.0 - q);
    outGradient = vec4(d * (k.coefficients.x * dw / r), 0.0);
}
