// realtime.particles.body_sphere_pixels with per_set = "gpu" (realtime/per_set.cpp): the bodies
// a frame draws as one sphere each (body_sphere_lod.h, chosen on the CPU), one word per body,
// at storage binding 1 (free in the render passes and in the per-set stages). Read by
// impostor.vert and halo.vert with BODY_MASK (a replaced body's particles are not drawn),
// gradient_gather.comp with BODY_MASK (their kernels are not summed) and per_set_pack.comp's
// REPLACED, which writes the counts (so that the frame's particles_drawn and droplets leave
// them out, as the CPU path's packing does). The variants without BODY_MASK do not declare it:
// a frame that replaces no body runs the programs it ran before.
#ifndef BODY_MASK_ACCESS
#define BODY_MASK_ACCESS readonly
#endif
layout(std430, binding = 1) BODY_MASK_ACCESS buffer BodyMask {
    uint replacedDrawn;     // REPLACED: the drawn particles of replaced bodies (droplets too)
    uint replacedDroplets;  // REPLACED: the droplets among them
    uint maskPadding[2];
    uint replacedBodies[];  // per body: 1 where its sphere is drawn instead, else 0
};

bool bodyReplaced(uint body) { return replacedBodies[body] != 0u; }
