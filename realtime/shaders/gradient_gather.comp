// realtime.particles.normal = "gradient" with per_set = "gpu", first half: at the surface point
// each pixel of the G-buffer holds, the colour field's exact gradient, the sum over every
// particle whose support covers it (v_j W'(|x - x_j|) (x - x_j) / |x - x_j|), gathered from the
// per-set grid (per_set.glsl's walk over the cells within reach) instead of splatted by one
// quad per kernel (gradient_splat.frag, which per_set = "cpu" keeps): no blending into a float
// target and no list of kernels to mark each frame; each pixel's sum in registers, in the
// grid's fixed order. gradient_resolve.frag turns the gradient into the normal.
// BODY_MASK (body_mask.glsl): the kernels of the bodies drawn as one sphere are left out, as
// per_set = "cpu" leaves them out of the splat (the sphere keeps its own normal). Where the
// replaced bodies lie apart from the others (no replaced body's supports' bounding sphere meets
// another's, every impostor within its particle's support: per_set.cpp), a replaced body's
// sphere lies within its bounding sphere, which no kernel that is summed reaches: its pixel
// takes 0 without a walk; another body's surface point lies within its own supports, which no
// replaced kernel reaches: its walk sums every entry it meets. Else (KERNEL_BODIES) every
// pixel is walked and each entry's body tested: a texel fetch more per entry, which llvmpipe
// pays even where no lane takes the branch (a 30k-particle ball: the gather 131 ms with the
// test, 74 ms without, medians on two loaded cores).
layout(local_size_x = 8, local_size_y = 8) in;
#include "common.glsl"
#include "per_set.glsl"
#ifdef BODY_MASK
#include "body_mask.glsl"
#endif
#if defined(BODY_MASK) && defined(KERNEL_BODIES)
#define SUMMED(k) !bodyReplaced(entryBody(k))
#define WALKED(body) true
#elif defined(BODY_MASK)
#define SUMMED(k) true
#define WALKED(body) !bodyReplaced(toIndex(body))
#else
#define SUMMED(k) true
#define WALKED(body) true
#endif

layout(binding = 0) uniform sampler2D uSurface;  // G-buffer: eye depth (+inf background), ...
layout(binding = 0, rgba32f) uniform writeonly image2D uGradient;
uniform dvec3 uCamera;  // the camera's world position (the G-buffer's points are relative to it)

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(uGradient)))) return;
    vec4 surface = texelFetch(uSurface, p, 0);  // eye depth, body, ...
    float z = surface.x;
    vec3 gradient = vec3(0.0);
    if (!isinf(z) && WALKED(surface.y)) {
        // The world point in double; each particle's offset from it rounded once to float.
        dvec3 x = uCamera + dvec3(surfacePosition(vec2(p) + 0.5, z));
        vec3 point = vec3(x);
#define ADD_GRADIENT(k)                                                                \
    {                                                                                  \
        vec4 e = entryPosition(k);                                                     \
        vec3 d = vec3(x - dvec3(e.xyz));                                               \
        float r = length(d);                                                           \
        float q = r * e.w;                                                             \
        if (q < 2.0 && r > 0.0 && SUMMED(k))                                           \
            gradient += d * (entryCoefficients(k).x * m4ShapeDerivative(q) / r);       \
    }
        FOR_EACH_NEAR(point, supportReach, ADD_GRADIENT)
#undef ADD_GRADIENT
    }
    imageStore(uGradient, p, vec4(gradient, 0.0));
}
