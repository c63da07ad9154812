// The particle storage buffer (realtime/gpu_scene.h, GpuParticle, std430, 112 bytes). With
// BODY_SPHERE the records are whole bodies' spheres, some fields read otherwise
// (packBodySpheres).
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

#ifdef ELLIPSOID
// realtime.particles.shape = "ellipsoid": one record per particle (realtime/gpu_scene.h,
// GpuEllipsoid, std430, 48 bytes). The ellipsoid is {centre + A u : |u| <= 1}, centre = the
// particle's position + (axisShift[0].w, axisShift[1].w, axisShift[2].w), A's columns the
// orthogonal semi-axis vectors axisShift[k].xyz (world, scene units).
struct EllipsoidRecord {
    vec4 axisShift[3];
};

layout(std430, binding = 4) readonly buffer Ellipsoids {
    EllipsoidRecord ellipsoids[];
};

// `A` (columns: orthogonal semi-axis vectors) and the inverse: row k is column k / |column k|^2.
mat3 ellipsoidAxes(EllipsoidRecord e, mat3 rotation) {
    return rotation * mat3(e.axisShift[0].xyz, e.axisShift[1].xyz, e.axisShift[2].xyz);
}
mat3 inverseAxes(mat3 axes) {
    return transpose(mat3(axes[0] / dot(axes[0], axes[0]), axes[1] / dot(axes[1], axes[1]),
                          axes[2] / dot(axes[2], axes[2])));
}
vec3 ellipsoidShift(EllipsoidRecord e) {
    return vec3(e.axisShift[0].w, e.axisShift[1].w, e.axisShift[2].w);
}
#endif
