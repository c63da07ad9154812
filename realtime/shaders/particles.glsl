// The particle storage buffer (realtime/gpu_scene.h, GpuParticle, std430, 112 bytes).
struct Particle {
    vec4 positionRadius;  // camera-relative world position; impostor radius (scene units)
    vec4 normalU;         // normal (world; not unit for the "field" model); u
    vec4 dudxV;           // d(u)/dx (1/scene unit); v
    vec4 dvdxBody;        // d(v)/dx; body index as float (exact below 2^24)
    vec4 glowMaterial;    // blackbody glow (linear RGB); material index as float
    vec4 hessianDiagonal;     // normal change per unit offset from the centre: xx, yy, zz
    vec4 hessianOffDiagonal;  // xy, xz, yz (zero: one normal for the whole impostor)
};

layout(std430, binding = 0) readonly buffer Particles {
    Particle particles[];
};

// Corners of the two triangles of a quad, in quad coordinates.
const vec2 QUAD_CORNERS[6] = vec2[](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0),
                                    vec2(-1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, 1.0));
