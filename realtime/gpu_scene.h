// The scene in the layouts the shaders read (std430 / std140): particles with camera-relative
// positions, material textures packed into one texel array, and the per-frame uniforms.
// Pure packing, no GL: the renderer uploads these.
#pragma once

#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <span>
#include <vector>

#include "core/body_sphere.h"
#include "core/particles.h"
#include "core/texture.h"
#include "realtime/anisotropy.h"
#include "realtime/field_normal.h"

namespace twinrender::realtime {

// shaders/particles.glsl, struct Particle (std430).
struct GpuParticle {
    glm::vec4 positionRadius;  // position - camera position (computed in double); radius
    glm::vec4 normalU;
    glm::vec4 dudxV;
    glm::vec4 dvdxBody;      // w: body index as float
    glm::vec4 glowMaterial;  // w: material index as float
    // The G-buffer normal's change over the impostor (field_normal.h; zero for "blend"): the
    // normal at x is normalize(normalU.xyz + H (x - centre)), H symmetric.
    glm::vec4 hessianDiagonal;     // xx, yy, zz, 0
    glm::vec4 hessianOffDiagonal;  // xy, xz, yz, 0
};
static_assert(sizeof(GpuParticle) == 112);

// Impostor radius = radii[i]. Body and material indices must stay below 2^24.
// `indices`: the particles to pack, in order (all of them when empty). `fieldNormals`: one per
// packed particle (realtime.particles.normal = "field"), or empty for the particle normal.
std::vector<GpuParticle> packParticles(const core::ParticleSet& particles,
                                       const glm::dvec3& cameraPosition,
                                       std::span<const float> radii,
                                       std::span<const std::uint32_t> indices = {},
                                       std::span<const FieldNormal> fieldNormals = {});

// realtime.particles.body_sphere_pixels: whole bodies drawn as one sphere each, in GpuParticle
// records that the BODY_SPHERE programs read (shaders/particles.glsl): positionRadius the
// sphere's centre (camera-relative) and radius, normalU, dudxV and dvdxBody.xyz the columns of
// the body's uv frame (core::BodyInfo::frame), hessianDiagonal.xyz the uv frame's origin
// relative to the sphere's centre, glowMaterial the particles' mean glow and the body's material.
std::vector<GpuParticle> packBodySpheres(std::span<const core::BodySphere> spheres,
                                         std::span<const core::BodyInfo> bodies,
                                         const glm::dvec3& cameraPosition);

// shaders/particles.glsl, struct EllipsoidRecord (std430; realtime.particles.shape =
// "ellipsoid"): the semi-axis vectors of one packed particle's ellipsoid (world space, scene
// units) in xyz, the shift of its centre from the particle's position in the w components.
struct GpuEllipsoid {
    glm::vec4 axisShift[3];
};
static_assert(sizeof(GpuEllipsoid) == 48);

// One record per packed particle: `indices` as for packParticles (all when empty).
std::vector<GpuEllipsoid> packEllipsoids(std::span<const Ellipsoid> ellipsoids,
                                         std::span<const std::uint32_t> indices = {});

// shaders/kernels.glsl, struct Kernel (std430): a particle's share of the colour field.
struct GpuKernel {
    glm::vec4 positionSupport;  // position - camera position (computed in double); 2 h
    glm::vec4 coefficients;     // v / (pi h^4), 1 / h, 0, 0
};
static_assert(sizeof(GpuKernel) == 32);

// The particles `indices` of the set (every particle when empty), in order.
std::vector<GpuKernel> packKernels(const core::ParticleSet& particles,
                                   const glm::dvec3& cameraPosition,
                                   std::span<const std::uint32_t> indices = {});

// shaders/textures.glsl, struct MaterialRecord (std430).
struct GpuMaterial {
    glm::ivec4 diffuse;  // x: first texel (RGB triple) in the texel array, y: width, z: height
    glm::ivec4 specular;
    glm::ivec4 emission;
    glm::ivec4 cityLights;
    glm::vec4 params;  // x: shininess
};
static_assert(sizeof(GpuMaterial) == 80);

struct GpuMaterials {
    std::vector<float> texels;  // RGB triples of every distinct texture, back to back
    std::vector<GpuMaterial> records;
};

// Identical textures (the same size and texels) are stored once.
GpuMaterials packMaterials(const std::vector<core::Material>& materials);

// shaders/common.glsl, uniform block FrameUniforms (std140).
struct FrameUniforms {
    glm::mat4 viewFromWorld{1.0f};
    glm::mat4 clipFromView{1.0f};
    glm::mat4 lightView{1.0f};
    glm::mat4 lightClip{1.0f};
    glm::vec4 viewport{0.0f};
    glm::vec4 camera{0.0f};
    glm::vec4 light{0.0f};
    glm::vec4 lightColor{0.0f};
    glm::vec4 shadowRange{0.0f};
    glm::vec4 shadowBias{0.0f};
    glm::vec4 misc{0.0f};      // exposure, radius scale, sphere normal weight, min impostor px
    glm::vec4 subpixel{0.0f};  // x: halo radius px (realtime.particles.halo_pixels); yzw: 0
};
static_assert(sizeof(FrameUniforms) == 4 * 64 + 8 * 16);

}  // namespace twinrender::realtime
