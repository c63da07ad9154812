// The frame as named passes (docs/design.md, "The real-time renderer"): shadow -> gbuffer ->
// normals -> ssss or surface -> ao -> shade -> post. Each pass takes the buffers it reads and
// returns the textures it writes; the renderer (renderer.cpp) runs them in order, times each with a
// GL timer query and skips the passes the settings do not need. Positions are camera-relative; the
// frame uniforms are bound at uniform binding 0, particles and materials at storage bindings 0 and
// 2 (ellipsoids at 4), the material texels at texture unit 7.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/atmosphere.h"
#include "core/particles.h"
#include "core/texture.h"
#include "realtime/gl/buffer.h"
#include "realtime/gl/buffer_texture.h"
#include "realtime/gl/framebuffer.h"
#include "realtime/gl/pipeline.h"
#include "realtime/gl/texture.h"
#include "realtime/gpu_scene.h"
#include "realtime/occlusion_spheres.h"
#include "realtime/settings.h"
#include "realtime/shader_library.h"

namespace twinrender::realtime {

class GpuPerSet;
struct OcclusionGridBuffers;

// What a draw takes (6 vertices per item): `count` items from item `first`, or, when
// `commands` is set, the indirect draw command a compute pass wrote there at byte `offset`
// (realtime/per_set_gpu.h).
struct DrawList {
    std::size_t count = 0;
    const gl::Buffer* commands = nullptr;
    std::size_t offset = 0;
    std::size_t first = 0;

    void draw() const;
};

// Buffers uploaded (or, with realtime.per_set = "gpu", packed by compute passes) per render.
struct SceneBuffers {
    gl::Buffer uniforms;          // FrameUniforms
    const gl::Buffer* particles;  // GpuParticle[]
    gl::BufferTexture texels;     // GpuMaterials::texels (RGB32F), texture unit 7
    gl::Buffer materials;         // GpuMaterial[]
    DrawList draw;                // the particles drawn
    // realtime.particles.shape = "ellipsoid": GpuEllipsoid[], one per particle, storage
    // binding 4; the impostor programs then take the ELLIPSOID variant (impostorDefines).
    const gl::Buffer* ellipsoids = nullptr;
    // Droplets (particles.droplet_atoms) among spheres: the droplets' ellipsoids, a draw of
    // their own after the spheres' with the ELLIPSOID variant (with realtime.per_set = "gpu"
    // their count is the GPU's: nothing is read back to choose the programs). Their particles
    // are the first of `particles`, their ellipsoids at the same index of `ellipsoids`, and the
    // spheres' draw starts after them.
    struct Droplets {
        const gl::Buffer* ellipsoids;  // GpuEllipsoid[]
        DrawList draw;
    };
    std::optional<Droplets> droplets;
    // realtime.particles.body_sphere_pixels: the bodies drawn as one sphere each
    // (packBodySpheres), after the particles, with the BODY_SPHERE variant (bodySphereDefines).
    struct BodySpheres {
        const gl::Buffer* records;  // GpuParticle[] as packBodySpheres fills them
        DrawList draw;
    };
    std::optional<BodySpheres> bodySpheres;
    // With realtime.per_set = "gpu", whose particles and droplets hold every body, the bodies
    // drawn as their sphere: one word per body after four of counts (shaders/body_mask.glsl),
    // nonzero where replaced. The programs that draw the particles then take the BODY_MASK
    // variant (bodyMaskDefines), which drops their particles; none in a frame that replaces none.
    struct BodyMask {
        const gl::Buffer* words;  // shaders/body_mask.glsl, storage binding 1
        // Whether a replaced body's kernels may reach another body's surface (its supports reach
        // that body's, or an impostor reaches beyond its particle's support): the gradient
        // gather then tests each kernel's body (GpuPerSet::gatherGradient).
        bool reachesOthers = true;
    };
    std::optional<BodyMask> bodyMask;

    void bind() const;
    // Draws the particles with impostor.vert and FRAGMENT (impostorDefines with `defines`,
    // bodyMaskDefines), then the droplets' ellipsoids, then the body spheres; leaves the
    // particles' buffers bound.
    // `frame`: other frame uniforms than `uniforms` (another projection), left bound.
    void drawImpostors(ProgramCache& programs, const char* fragment,
                       const std::vector<std::string>& defines,
                       const gl::Buffer* frame = nullptr) const;
};

// `defines` with the one that selects the impostor shape of impostor.vert, gbuffer.frag and
// shadow.frag: ELLIPSOID when `ellipsoids`.
std::vector<std::string> impostorDefines(bool ellipsoids, std::vector<std::string> defines);

// `defines` with BODY_SPHERE: the whole-body sphere's variant of impostor.vert and its fragment.
std::vector<std::string> bodySphereDefines(std::vector<std::string> defines);

// `defines` with BODY_MASK where `bodyMask` (SceneBuffers::bodyMask): the variant of
// impostor.vert and halo.vert that drops the particles of the bodies drawn as one sphere (and
// of gradient_gather.comp that leaves out their kernels).
std::vector<std::string> bodyMaskDefines(bool bodyMask, std::vector<std::string> defines);

// The #define selecting the depth encoding in common.glsl.
const char* depthDefine(DepthMode mode);
// The shade pass's define for the shadows: SHADOWS_ and the mode's name in capitals.
std::string shadowDefine(ShadowMode mode);
// The shade pass's defines: the shadows' (with ESM_SEED for the seed's form of ESM), EMISSION
// when anything emits, AMBIENT_OCCLUSION when the ambient occlusion pass runs, EMISSIVE_LIGHT
// when the emissive pass does.
std::vector<std::string> shadeDefines(ShadowMode mode, const ShadowMapSettings& shadowMap,
                                      bool emission, bool ambientOcclusion = false,
                                      bool emissiveLight = false);

// shadow: the impostors seen from the light into a resolution^2 float depth map holding
// linear light depth in [0, 1]; for the filtered modes ("esm", "vsm", "evsm") that map turned
// into theirs (one, two or four float channels, linear filtering) and blurred by
// settings.blurRadius texels.
gl::Texture runShadowPass(ProgramCache& programs, const SceneBuffers& scene, ShadowMode mode,
                          const ShadowMapSettings& settings);
// The defines of shaders/shadow_moments.frag for a filtered mode, and the exponents it and the
// shade pass take: ESM (c, 0), EVSM (c+, c-).
std::vector<std::string> shadowMomentsDefines(ShadowMode mode, const ShadowMapSettings& settings);
glm::vec2 shadowExponents(ShadowMode mode, const ShadowMapSettings& settings);

// gbuffer: impostors from the camera, depth test in the selected encoding.
struct GBuffer {
    // RGBA32F, or RGBA16F with gbuffer.format = "compact": world normal (octahedral,
    // octahedral.h), u, v
    gl::Texture normalUv;
    gl::Texture emission;  // RGBA32F (RGBA16F "compact"): emission, 0
    gl::Texture surface;   // RGBA32F: eye depth (+inf background), body (-1), radius px, material
    gl::Texture depth;     // Depth24 (standard) or Depth32F
    gl::Framebuffer framebuffer;
};
GBuffer runGBufferPass(ProgramCache& programs, const SceneBuffers& scene, int width, int height,
                       DepthMode mode, GBufferFormat format);
// The G-buffer's bytes per pixel (its three colour targets and depth), for the frame's
// gbuffer_bytes counter.
std::size_t gbufferBytesPerPixel(GBufferFormat format, DepthMode mode);

// gradient (realtime.particles.normal = "gradient"): the G-buffer's normal + uv with the normal
// replaced by the colour field's exact gradient direction at each covered pixel's surface point,
// summed over `kernels` (GpuKernel[], every particle of the set).
gl::Texture runGradientNormalPass(ProgramCache& programs, const SceneBuffers& scene,
                                  const gl::Buffer& kernels, const DrawList& kernelDraw,
                                  const GBuffer& gbuffer, DepthMode mode);
// The same with the gradient gathered through `perSet`'s grid (per_set = "gpu": no kernels
// splatted); `camera` the camera's world position.
gl::Texture runGradientGatherPass(ProgramCache& programs, const SceneBuffers& scene,
                                  GpuPerSet& perSet, const glm::dvec3& camera,
                                  const GBuffer& gbuffer, DepthMode mode);

// Full-screen passes that only need covered pixels (ssss, shade) draw with this state and put
// fullscreen.vert's triangle at coveredOnlyDepth(): the G-buffer's depth attachment then
// rejects background pixels before their fragment shader runs.
gl::PipelineState coveredOnlyState(DepthMode mode);
float coveredOnlyDepth(DepthMode mode);

// ssss: the smoothed normal + uv and, when `emission` (the scene emits anywhere), the smoothed
// emission (ping-pong targets); without, the G-buffer's (zero) emission stands.
struct SmoothedSurface {
    gl::Texture normalUv[2];
    gl::Texture emission[2];  // empty when the emission is not smoothed
    int current = 0;          // the targets holding the result
};
// `normalUv`: the normal + uv to smooth (the G-buffer's, or the gradient pass's).
SmoothedSurface runSsssPass(ProgramCache& programs, const GBuffer& gbuffer,
                            const gl::Texture& normalUv, const SsssSettings& settings,
                            bool emission, DepthMode mode);

// surface (surface.method = "bilateral" | "narrow_range" | "curvature_flow" | "shader"): what
// the shade pass reads after a depth filter (normals rebuilt from the filtered depth, uv and
// emission as drawn) or after the user's shader.
struct FilteredSurface {
    std::optional<gl::Texture> surface;   // as GBuffer::surface; empty: the G-buffer's stands
    gl::Texture normalUv;                 // world normal (octahedral), u, v
    std::optional<gl::Texture> emission;  // the user's shader only; empty: the G-buffer's
};
// `normalUv`: the normal + uv drawn (the G-buffer's, or the gradient pass's).
FilteredSurface runSurfacePass(ProgramCache& programs, const GBuffer& gbuffer,
                               const gl::Texture& normalUv, const SurfaceSettings& settings);
// Compiles the programs runSurfacePass will use with these settings.
void compileSurfacePrograms(ProgramCache& programs, const SurfaceSettings& settings);
// The program of the user's shader (surface.shader), compiled on first use; throws
// core::InputError naming the file, with the compiler's messages by file and line.
const gl::Program& userSurfaceProgram(ProgramCache& programs, const SurfaceSettings& settings);

// ao (ao.method is not "none"): the open fraction of each covered pixel's hemisphere within
// `radius` (light.ao_radius, scene units; 0: 1 everywhere), from the surface and normals the
// shade pass reads, then blurred (ao.blur). R32F, background texels 1.
// `back` (ao.layers = 2): the second depth layer, runBackLayerPass's. ao.method = "traced"
// traces rays through `grid` (ao_traced.h), which must then be given.
gl::Texture runAmbientOcclusionPass(ProgramCache& programs, const gl::Texture& surface,
                                    const gl::Texture& normalUv, const AoSettings& settings,
                                    double radius, const gl::Texture* back = nullptr,
                                    const OcclusionGridBuffers* grid = nullptr);
// The defines of shaders/ao.frag (or ao_traced.frag) for these settings (the method's and the
// noise's).
std::vector<std::string> ambientOcclusionDefines(const AoSettings& settings);
// The occlusion pass's second depth layer (ao.layers = 2): per pixel, the eye depth where the
// view ray leaves the body `surface` holds there (the farthest far side of that body's
// impostors along the ray); 0 where none. R32F.
gl::Texture runBackLayerPass(ProgramCache& programs, const SceneBuffers& scene,
                             const gl::Texture& surface, DepthMode mode);
// gbuffer.frag's defines for that layer.
std::vector<std::string> backLayerDefines(DepthMode mode);

// emissive (usesEmissiveLight): the irradiance E (rgb, linear; a unused) that emitting
// surfaces cast on each covered pixel, from the surface, normals and emission the shade pass
// reads, by emissive.method (realtime/emissive_pass.cpp). RGBA32F, background texels 0.
// "point_lights": `emitters` (pointLights), with no shadowing; "ssem": rays marched on screen,
// then blurred (emissive.blur); "ssem_target": rays marched in the emitter target (the
// emitting impostors alone, drawn with `frame` widened by emitterTargetUniforms), then blurred.
struct PointLight {
    glm::vec3 centre{0.0f};     // camera-relative
    float radius = 0.0f;        // the body's surface radius R (core::EmittingBody)
    glm::vec3 intensity{0.0f};  // pi R^2 L, L the body's mean radiance (linear RGB)
    std::uint32_t body = 0;     // its own surface is not lit by it
};
// At most this many point lights: the brightest by intensity (the sum of its channels).
inline constexpr std::size_t MAX_POINT_LIGHTS = 16;
// The point lights of the scene's emitting bodies (core::emittingBodies), positions relative
// to `camera`, the brightest MAX_POINT_LIGHTS of them.
std::vector<PointLight> pointLights(const core::SceneParticles& particles,
                                    const std::vector<core::Material>& materials,
                                    const glm::dvec3& camera);
gl::Texture runEmissivePass(ProgramCache& programs, const gl::Texture& surface,
                            const gl::Texture& normalUv, const gl::Texture& emission,
                            const EmissiveSettings& settings,
                            const std::vector<PointLight>& emitters, const SceneBuffers& scene,
                            const FrameUniforms& frame, DepthMode mode);
// "ssem_target": the frame uniforms the emitter target is drawn with: the camera's position and
// orientation, tan(fov' / 2) = emissive.target_fov_scale tan(fov / 2), the camera's aspect and
// resolution (emissive.target_aspect) or a square of its height.
FrameUniforms emitterTargetUniforms(const FrameUniforms& frame, const EmissiveSettings& settings,
                                    DepthMode mode);
// The impostor defines (with impostorDefines) the emitter target is drawn with.
std::vector<std::string> emitterTargetDefines(DepthMode mode);
// The fragment shaders (with fullscreen.vert) the emissive pass draws with these settings, in
// order: the estimate, then the blur's.
struct EmissiveProgram {
    const char* fragment = nullptr;
    std::vector<std::string> defines = {};
};
std::vector<EmissiveProgram> emissivePrograms(const EmissiveSettings& settings);

// A separable blur of `open[0]` (fullscreen.vert with ao_blur.frag's variants: the image at
// binding 0, uniforms uRadius, uDirection, uDepth) by `radius` pixels: horizontally into `open[1]`
// through `targets[1]`, then vertically back into `open[0]` through `targets[0]`.
void blurSeparably(const gl::Program& blur, int radius, const gl::Texture (&open)[2],
                   const gl::Framebuffer (&targets)[2]);

// shade: beauty (rgb) and light visibility (a). `shadowMap` may be null (no map).
struct ShadeInputs {
    const gl::Texture* normalUv = nullptr;
    const gl::Texture* emissionBuffer = nullptr;
    const gl::Texture* surface = nullptr;
    const gl::Texture* depth = nullptr;  // the G-buffer's depth attachment
    DepthMode depthMode = DepthMode::Log;
    const gl::Texture* shadowMap = nullptr;
    ShadowMode shadows = ShadowMode::None;
    ShadowMapSettings shadowSettings;  // the filtered modes' exponents and bleed reduction
    bool emission = true;              // false: the emission buffer is zero and need not be read
    // The ambient occlusion pass's open fraction (binding 4), multiplying the ambient term;
    // null: no occlusion.
    const gl::Texture* ambientOcclusion = nullptr;
    // The emissive pass's irradiance (binding 5), lighting the albedo; null: none.
    const gl::Texture* irradiance = nullptr;
    // The sun's visibility per pixel (R32F, binding 3) instead of the shadows' test: the error
    // split's exact light (VISIBILITY_TEXTURE). Null: the shadows of `shadows`.
    const gl::Texture* visibility = nullptr;
    // Spheres mode: camera-relative centres.
    std::vector<OcclusionSphere> spheres;
};
gl::Texture runShadePass(ProgramCache& programs, const ShadeInputs& inputs);

// halo (realtime.particles.halo_pixels, spheres): each sphere impostor projected smaller than
// that radius that emits adds its flux to `beauty` as a Gaussian of its own spread (its G-buffer
// pixels emit nothing), where `surface` (the G-buffer's eye depth) holds nothing nearer than
// its front.
void runHaloPass(ProgramCache& programs, const SceneBuffers& scene, const gl::Texture& surface,
                 const gl::Texture& beauty);

// atmosphere (a body of the scene has one, core/atmosphere.h): each pixel's view ray through
// the shell up to the end point settings.endPoint picks (the G-buffer's impostor depth, the
// depth the shade pass read, the analytic inner sphere, or the seed's blend of the last two by
// distance), with core's quadrature mirrored in shaders/atmosphere.glsl.
struct AtmosphereInputs {
    const gl::Texture* beauty = nullptr;    // the shade pass's
    const gl::Texture* impostor = nullptr;  // the G-buffer's surface (eye depth, body)
    const gl::Texture* filtered = nullptr;  // the surface the shade pass read
    core::Atmosphere atmosphere;  // its steps: atmosphere.steps where set, else the scene's
    glm::dvec3 camera{0.0};       // world position
    AtmosphereSettings settings;
};
// RGBA32F both: beauty x T + L_in (a: the visibility, kept), and L_in (a: 0).
struct AtmosphereTargets {
    gl::Texture beauty, inscatter;
};
AtmosphereTargets runAtmospherePass(ProgramCache& programs, const AtmosphereInputs& inputs);
// The #define selecting the end point in shaders/atmosphere.frag.
std::vector<std::string> atmosphereDefines(const AtmosphereSettings& settings);

// post: bloom (when enabled) and the tonemapper into display values (RGBA32F, a = 1).
gl::Texture runPostPass(ProgramCache& programs, const gl::Texture& beauty,
                        const BloomSettings& bloom, float exposure);

}  // namespace twinrender::realtime
