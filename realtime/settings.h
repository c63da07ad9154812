// Settings of the real-time renderer: the [realtime] table of a scene (and --set realtime.*),
// read in exactly one place, parseSettings(). Keys are the dotted names in the comments.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "core/parameters.h"

namespace twinrender::realtime {

// How the depth buffer stores depth (docs/scenes.md, realtime.depth). The Z channel of the frame is
// linear eye depth in every mode.
// How the G-buffer stores the normal, uv and emission (docs/scenes.md, realtime.gbuffer.format).
enum class GBufferFormat {
    Full,     // "full": 32-bit floats (48 bytes a pixel with the surface target)
    Compact,  // "compact": 16-bit floats for normal + uv and emission (32 bytes a pixel)
};

enum class DepthMode {
    Standard,  // "standard": the perspective z/w in a 24-bit fixed-point buffer (GL's default)
    Log,       // "log": log2(1 + z/near) / log2(1 + far/near) in a float buffer
    Reversed,  // "reversed": reversed-Z (near -> 1, far -> 0) in a float buffer
};

enum class ShadowMode {
    None,     // "none": no shadow pass; every surface is lit (visibility 1)
    Map,      // "map": orthographic shadow map of the particle impostors, one tap
    Pcf,      // "pcf": the same map, percentage-closer filtered
    Spheres,  // "spheres": the old baseline; one occluding sphere per body over 5 % of particles
    // The filtered maps: the depth map turned into a map that may be blurred and filtered
    // linearly (realtime/shadow_pass.cpp), then read with bilinear taps.
    Esm,   // "esm": exponential shadow map (Annen et al. 2008), in the form of esm_form
    Vsm,   // "vsm": variance shadow map, depth and depth squared (Donnelly & Lauritzen 2006)
    Evsm,  // "evsm": exponential variance shadow map, positive and negative warps (Lauritzen 2008)
};

// The two forms of ESM (shadow_map.esm_form).
enum class EsmForm {
    // "seed": the depth map blurred, then visibility = clamp(exp(c (blurred depth - receiver
    // depth)), 0, 1), as the WebGL planet renderer this project grew from did. The exponential
    // of a blurred depth is not the blur of exponentials: across an edge it is darker or
    // lighter than the filtered test.
    Seed,
    // "warp": exp(c depth) stored and blurred, times exp(-c receiver depth): the filtered
    // exponential test of Annen et al.
    Warp,
};

// What normal the G-buffer writes per fragment (particles.normal).
enum class NormalModel {
    Sphere,    // "sphere": the impostor's own normal (the ellipsoid's with shape = "ellipsoid")
    Field,     // "field": the colour field's gradient, modelled to first order over each
               // impostor (realtime/field_normal.h)
    Blend,     // "blend": the particle normal blended with the impostor sphere's normal by
               // sphere_normal_weight (one direction per particle, plus the sphere's bulge)
    Gradient,  // "gradient": the colour field's exact gradient at each pixel's surface point,
               // every particle's kernel added by a pass of its own (shaders/gradient_*.frag)
};

// How each particle's impostor radius is chosen (particles.radius; realtime/impostor_radius.h).
enum class RadiusModel {
    Field,  // "field": the distance along the normal to the level set, at most radius_scale * h
    Fixed,  // "fixed": radius_scale * h for every particle
};

// The impostor's shape (particles.shape; realtime/anisotropy.h).
enum class ParticleShape {
    Sphere,     // "sphere": a sphere of the impostor radius about the particle
    Ellipsoid,  // "ellipsoid": stretched along the neighbourhood's spread (Yu & Turk 2013)
};

// Where an ellipsoid sits along its particle's normal (particles.anisotropy.anchor).
enum class EllipsoidAnchor {
    Surface,  // "surface": as far along the normal as the impostor sphere reaches
    Centre,   // "centre": about the smoothed centre (Yu & Turk)
};

// particles.anisotropy.*: the ellipsoids of shape = "ellipsoid" (realtime/anisotropy.h). The
// paper's constants, except its size scale k_s (a covariance in its scene's units): an
// ellipsoid has the volume of the particle's impostor sphere instead.
struct AnisotropySettings {
    // particles.anisotropy.smoothing: lambda, how far the ellipsoid's centre moves from the
    // particle towards its neighbourhood's weighted mean, 0..1 (0: not at all). The paper's
    // Laplacian smoothing of kernel centres, lambda "close to 1".
    double smoothing = 0.9;
    // particles.anisotropy.max_axis_ratio: k_r, the largest ratio of the longest axis to the
    // others, 1..16 (1: spheres). The paper's 4.
    double maxAxisRatio = 4.0;
    // particles.anisotropy.min_neighbours: N_eps, particles with fewer neighbours within 2 h
    // (themselves not counted) stay spheres, 1..1000. The paper's 25.
    int minNeighbours = 25;
    // particles.anisotropy.anchor: "surface" | "centre". About the smoothed centre, a surface
    // particle's ellipsoid (flattened across the surface, pulled inwards by the smoothing)
    // ends a good part of a radius below the level set its impostor sphere reaches: coverage
    // IoU 0.871 on the planet against 0.988 for spheres, depth error 10x. "surface" moves it
    // along the particle's normal until it reaches as far as the sphere (the smoothing then
    // acts along the surface only): 0.981, depth error 1.2x (realtime/README.md).
    EllipsoidAnchor anchor = EllipsoidAnchor::Surface;
    bool operator==(const AnisotropySettings&) const = default;
};

struct ParticleSettings {
    // particles.radius_scale: impostor sphere radius / smoothing length h, (0, 10].
    // The M4 level set at 0.13 lies 0.92 h (hcp) to 0.94 h (cubic) above the outermost layer
    // of a flat lattice (h = 1.3 s); on curved bodies the spheres' scalloped outline matches
    // it best a little lower: 0.9 gives the least depth error against the raymarcher on the
    // planet, opensph_ball and contact scenes (coverage IoU 0.98; realtime/README.md).
    double radiusScale = 0.9;
    // particles.radius: "field" | "fixed" (realtime/impostor_radius.h).
    RadiusModel radius = RadiusModel::Field;
    // particles.surface_level: the colour-field level whose surface "field" radii reach, > 0;
    // the raymarcher's raymarch.surface_level (0.13, as OpenSPH) unless set.
    double surfaceLevel = 0.13;
    // particles.crossing_scale ("field" only): the radius is this times the distance to the
    // crossing along the normal (at most radius_scale * h), [1, 4]; a particle alone in its
    // support keeps the crossing itself, its droplet's exact radius. The crossing along the
    // normal is the nearest the level set comes on that side; between particles the smooth
    // level set bulges beyond the union of such spheres. Coverage IoU on the LAMMPS splash
    // frames 0/12/20/40 at 320 x 240: 0.979/0.939/0.938/0.928 at 1.2, -/0.931/0.929/0.924 at
    // 1.1, 0.974/0.943/0.938/0.922 at 1.3, 0.968/0.939/0.930/0.911 at 1.4 (docs/methods.md).
    double crossingScale = 1.2;
    // particles.interior_level ("field" only): a particle whose colour field at its centre is at
    // least this (and above surface_level and its own kernel's peak) lies deep inside a body,
    // and its radius is radius_scale h without the search along its normal, > 0. The field must
    // fall from here to surface_level within radius_scale h along the normal for this to change a
    // radius: at 0.8 it changes none on any default scene or frame of the two real sequences, while
    // 95 % of a million-particle planet's particles are settled by it. Their normals are derived
    // only where they are drawn (per_set = "gpu"; realtime/per_set_gpu.h).
    double interiorLevel = 0.8;
    // particles.droplet_atoms ("field" only): clusters of 2 to this many sparse particles are
    // drawn as one ellipsoid fitted to their level-set droplet (realtime/droplets.h), 0..64
    // (below 2: none). A pair's droplet is a capsule whose neck no sphere about a particle
    // covers.
    int dropletAtoms = 8;
    // particles.normal: "gradient" | "field" | "blend" | "sphere". The particle normal (the
    // colour-field gradient at the centre) is one direction per particle, while the rendered
    // surface turns across a particle; "field" follows the field's gradient over the impostor to
    // first order: mean normal error on the planet 2.9 degrees without SSSS, against 5.4 for
    // "blend" (README).
    NormalModel normal = NormalModel::Gradient;
    // particles.sphere_normal_weight ("blend" only): the G-buffer normal is
    // normalize(mix(particle normal, impostor sphere normal, weight)), 0..1. At a surface point
    // the particle's own kernel adds a term along the sphere normal. 0.25 minimises the normal
    // error against the raymarcher (README).
    double sphereNormalWeight = 0.25;
    // particles.cull_hidden: skip particles whose impostor lies inside the union of its
    // neighbours' (realtime/occlusion_culling.h); the image does not change, only the cost.
    // Spheres only: the test is exact for spheres, so ellipsoids are never culled.
    bool cullHidden = true;
    // particles.min_pixels: a sphere impostor projected smaller than this radius (pixels) is
    // drawn as a splat of its flux (projected area times emission) over the pixels within one
    // of its centre, weighted by a bilinear tent whose weights sum to 1 wherever the centre
    // lies, 0..64 (0: off, every impostor drawn as its sphere; about 1 is meant). Drawn as a
    // sphere it covers few pixel centres or none: its light vanishes or flickers as it moves,
    // while the reference integrates its coverage (study subpixel_emitters). Only the emission
    // keeps its flux: the G-buffer holds one opaque surface per pixel, so the splat's pixels
    // reflect light as the whole surface would and hide what lies behind them. Per impostor: a
    // body of many particles keeps only the front one's flux. Spheres only.
    double minPixels = 0.0;
    // particles.halo_pixels: a sphere impostor projected smaller than this radius (pixels)
    // gives its emitted light to a halo instead, 0..64 (0: off; the alternative to min_pixels,
    // not to be set with it). The halo is a Gaussian of the disc's own spread (sigma = its
    // projected radius / sqrt(2), at least 0.7 px), carrying its flux (projected area times
    // emission), added to the linear beauty after shading where nothing nearer hides the
    // sphere's front (realtime/halo_pass.cpp). A sampled Gaussian of sigma >= 0.7 px sums to 1
    // within 0.03 % wherever its centre lies, so the flux is kept at any position and size below
    // the threshold; the sphere is still drawn, reflecting light, with no emission of its own.
    // Per impostor, spheres only (droplets' ellipsoids keep their emission).
    double haloPixels = 0.0;
    // particles.body_sphere_pixels: a body whose level-set sphere (core/body_sphere.h) projects
    // to a radius below this many pixels is drawn as that one analytic sphere (its normal the
    // sphere's, uv its body-local spherical angles, glow its particles' mean) instead of its
    // particles, 0..4096 (0: off, every particle drawn). Decided per body per frame on the CPU,
    // with either per_set (on the GPU a mask of the replaced bodies). Study body_sphere.
    double bodySpherePixels = 0.0;
    // particles.shape: "sphere" | "ellipsoid".
    ParticleShape shape = ParticleShape::Sphere;
    AnisotropySettings anisotropy;  // shape = "ellipsoid"
};

struct ShadowMapSettings {
    int resolution = 2048;  // shadow_map.resolution: texels per side, 16..16384
    // Depth bias = (bias + slope_bias * tan(angle between normal and light)) * unit, the unit
    // being the larger of the receiving particle's radius and a shadow-map texel: impostor
    // surfaces are bumpy on the scale of a particle, the map is coarse on that of a texel.
    // The tangent is capped at 10.
    double bias = 0.5;       // shadow_map.bias: 0..10
    double slopeBias = 1.0;  // shadow_map.slope_bias: 0..100
    double pcfRadius = 1.5;  // shadow_map.pcf_radius: "pcf" filter radius, texels, 0..16
    // shadow_map.blur_radius: "esm", "vsm", "evsm": the separable box blur of the filtered map,
    // texels on each side of the centre, 0..16 (0: no blur; the bilinear taps still filter).
    // A fractional radius weighs the outermost texels by its fraction.
    double blurRadius = 2.0;
    // shadow_map.esm_exponent: c, per unit of normalised light depth (0..1 over the map's
    // depth range), 0..80. Larger leaks less light close behind an occluder and sharpens the
    // edges. The warp form stores exp(c depth): c depth must stay below ln(FLT_MAX) = 88.7 to
    // fit a 32-bit float, and 80 leaves room for the blur's and bilinear taps' rounding.
    double esmExponent = 80.0;
    EsmForm esmForm = EsmForm::Warp;  // shadow_map.esm_form: "seed" | "warp"
    // shadow_map.vsm_bleed_reduction: "vsm" and "evsm": the Chebyshev bound's values below this
    // become 0 and the rest are rescaled to [0, 1], [0, 0.99]; trades light bleeding where
    // casters overlap for darker, harder penumbrae.
    double vsmBleedReduction = 0.2;
    // shadow_map.evsm_positive_exponent and evsm_negative_exponent: c+ and c- of EVSM's warps
    // exp(c+ d) and -exp(-c- d), per unit of normalised depth, 0..42. The second moments are
    // exp(2 c d), which must stay below FLT_MAX = exp(88.7) in the 32-bit map: c <= 44, 42
    // with headroom.
    double evsmPositiveExponent = 40.0;
    double evsmNegativeExponent = 5.0;
};

struct SsssSettings {
    bool enabled = true;  // ssss.enabled: Screen-Space Surface Smoothing of uv, normal, emission
    // ssss.radius_scale: blur radius / projected particle radius, 0..16 (0 = no blur). Larger
    // hides more of the particles in uv (texture), smaller keeps the surface's real ripples in
    // the normals. With the exact gradient normals, 0.3 is on the Pareto front of frame time
    // against normal error of `twinrender study methods` (docs/methods.md): median over the 8
    // default scenes 1.19 degrees against 1.21 without SSSS and 1.66 at 0.6 (the default when
    // normals were modelled per particle), FLIP 0.038 against 0.042 at 0.6, uv error 6 %
    // below no SSSS.
    double radiusScale = 0.3;
    // ssss.depth_limit: largest eye-depth difference between blurred pixels, in radii of the
    // centre pixel's particle, (0, 1000].
    double depthLimit = 3.0;
    int iterations = 1;     // ssss.iterations: the filter applied this many times, 1..16
    bool separable = true;  // ssss.separable: horizontal then vertical; false: the full 2-D kernel
    // ssss.max_taps: samples on each side of the centre (per axis in 2-D), 1..64; wider radii
    // are sampled every radius / max_taps pixels. 4 costs half of 8 for 0.05 deg of normal error.
    int maxTaps = 4;
};

// How the surface is smoothed before shading (surface.method; docs/methods.md compares them).
enum class SurfaceMethod {
    Ssss,           // "ssss": Screen-Space Surface Smoothing of normal, uv and emission
    Bilateral,      // "bilateral": bilateral filter of eye depth (van der Laan et al. 2009)
    NarrowRange,    // "narrow_range": narrow-range filter of eye depth (Truong & Yuksel 2018)
    CurvatureFlow,  // "curvature_flow": screen-space curvature flow of eye depth (van der Laan)
    None,           // "none": the G-buffer as drawn
    Shader,         // "shader": the user's fragment shader (surface.shader)
};

// The depth filters write a new eye depth; normals are then rebuilt from it (one-sided
// differences, the smaller depth step per axis); uv and emission stay as drawn. Every filter
// leaves other bodies' pixels and the background out. Lengths are in particle radii (the
// radius of the impostor drawn at the centre pixel), so a filter does the same at every
// distance.
struct BilateralSettings {
    // surface.bilateral.radius: kernel radius, 1 = the projected particle radius (as NVIDIA
    // FleX: a blur radius of half the particle's diameter), (0, 16]. Spatial weight
    // exp(-(d / radius)^2).
    double radius = 1.0;
    // surface.bilateral.depth_sigma: the range weight's sigma, exp(-dz^2 / 2 sigma^2), in particle
    // radii, (0, 1000]: 10/3 as the bilateral baseline of Truong & Yuksel 2018.
    double depthSigma = 10.0 / 3.0;
    int iterations = 1;      // surface.bilateral.iterations: 1..16 (FleX: 1)
    bool separable = false;  // surface.bilateral.separable: horizontal then vertical (Green 2010)
    double maxRadiusPx = 5;  // surface.bilateral.max_radius_px: cap, 1..64 (FleX: 5)
};

struct NarrowRangeSettings {
    // surface.narrow_range.radius: filter size in particle radii, (0, 16]; the Gaussian's sigma
    // is a third of it. 0.5 as the authors' demo (0.1 * filter size 5).
    double radius = 0.5;
    // surface.narrow_range.threshold: delta, the half-width of the depth range that counts, in
    // particle radii, (0, 1000]: samples nearer than it are dropped (with their mirror).
    double threshold = 10.5;
    // surface.narrow_range.clamp: mu, in particle radii, [0, 1000]: samples beyond the range
    // (the background included) count as this far behind the centre.
    double clamp = 1.0;
    int iterations = 3;  // surface.narrow_range.iterations: 1..16
    // surface.narrow_range.separable: iterations - 1 rounds of 1-D passes (x then y) and one
    // final 2-D pass of 4 pixels, as the paper; false: every round the full 2-D kernel.
    bool separable = true;
    double maxRadiusPx = 100;  // surface.narrow_range.max_radius_px: cap, 1..256
};

struct CurvatureFlowSettings {
    // surface.curvature_flow.iterations: explicit steps of dz/dt = H, 0..500.
    int iterations = 40;
    // surface.curvature_flow.time_step: each step moves depth by time_step * (pixel footprint)
    // * H, a diffusion of time_step pixels^2 on a flat surface, (0, 0.25] (stable at every
    // depth; the reach after n steps is about sqrt(2 n time_step) pixels).
    double timeStep = 0.2;
    // surface.curvature_flow.depth_limit: larger depth steps between neighbours, in particle
    // radii, are edges: their derivatives count as zero, (0, 1000]: 5 as the authors' demo.
    double depthLimit = 5.0;
};

struct SurfaceSettings {
    // surface.method: "ssss" | "bilateral" | "narrow_range" | "curvature_flow" | "none" |
    // "shader"; "shader" when only surface.shader is given.
    SurfaceMethod method = SurfaceMethod::Ssss;
    // surface.shader: a GLSL file (relative to the scene file) defining
    // void filterSurface(ivec2 pixel, inout SurfaceSample s) (realtime/shaders/user_surface.frag
    // says what it may read); `shaderPath` is the resolved path, `shaderSource` its text.
    std::string shaderPath, shaderSource;
    int shaderPasses = 1;        // surface.shader_passes: the shader applied this many times, 1..64
    bool shaderNormals = false;  // surface.shader_normals: rebuild normals from its depth after
    BilateralSettings bilateral;
    NarrowRangeSettings narrowRange;
    CurvatureFlowSettings curvatureFlow;
};

struct BloomSettings {
    bool enabled = true;     // bloom.enabled: bloom in the PNG (never in the EXR)
    double strength = 0.05;  // bloom.strength: weight of the bloom added to the beauty, 0..10
    double threshold = 1.0;  // bloom.threshold: linear radiance above which pixels bloom, >= 0
};

// Where the work done once per particle set runs (per_set): impostor radii, the kernels that
// reach the surface, occlusion culling, field normal models, ellipsoids (realtime/README.md).
enum class PerSetDevice {
    Gpu,  // "gpu": compute shaders over a uniform grid built on the GPU (per_set_gpu.h)
    Cpu,  // "cpu": oneTBB over core::ColourField's grids, packed and uploaded
};

// ao.*: the ambient occlusion pass (realtime/ao_pass.cpp, shaders/ao.frag; "traced":
// realtime/ao_traced.h, shaders/ao_traced.frag). Its reach is the scene's light.ao_radius, which
// the reference traces exactly.
enum class AoMethod {
    None,  // "none": no pass; the ambient term is not occluded
    Ssao,  // "ssao": points in the normal's hemisphere tested against the depth buffer
    Hbao,  // "hbao": horizon-based (Bavoil & Sainz 2008)
    Gtao,  // "gtao": ground-truth AO (Jimenez et al. 2016), cosine-weighted horizons
    // "traced": rays in world space from each pixel's surface point against the particles'
    // impostor spheres through a uniform grid (realtime/ao_traced.h)
    Traced,
};
enum class AoBlur {
    None,        // "none": the raw, noisy estimate
    Flat,        // "flat": a separable Gaussian over covered pixels
    DepthAware,  // "depth_aware": the same, weighted by depth closeness and the same body
};
enum class AoNoise {
    White,                // "white": a per-pixel hash
    InterleavedGradient,  // "interleaved_gradient": Jimenez 2014's low-discrepancy pattern
    Blue,                 // "blue": a tiled void-and-cluster texture (realtime/blue_noise.h)
};
// The depth the occlusion pass reads.
enum class AoDepth {
    Shaded,    // "shaded": the depth the shade pass reads (a depth filter's, else the impostors')
    Filtered,  // "filtered": a depth filter's; where the surface method filters no depth (ssss,
               // none), the narrow-range filter (surface.narrow_range.*) and the normals rebuilt
               // from it, run for the occlusion pass alone
};
struct AoSettings {
    // ao.method: "none" | "ssao" | "hbao" | "gtao" | "traced". "traced" by default: in the
    // ambient_occlusion study it alone lowers the error against none wherever the truth is
    // occluded on each of its scenes, within the bound on false occlusion where it is open. It
    // runs where the scene's light.ao_radius is above 0.
    AoMethod method = AoMethod::Traced;
    // ao.slices: screen directions per pixel (hbao: over a full turn; gtao: slices over half a
    // turn, two sides each; ssao: slices x steps points), 1..32.
    int slices = 4;
    int steps = 8;  // ao.steps: samples along each direction (or per ssao slice), 1..64
    // ao.rays ("traced" only): cosine-weighted rays per pixel, stratified over the disc, 1..256.
    int rays = 16;
    // ao.blur: "none" | "flat" | "depth_aware"; ao.blur_radius: pixels, 1..16.
    AoBlur blur = AoBlur::DepthAware;
    int blurRadius = 4;
    // ao.noise: "white" | "interleaved_gradient" | "blue"
    AoNoise noise = AoNoise::InterleavedGradient;
    // ao.max_pixels: the cap of the radius on screen, pixels, 4..4096 (a point near the camera
    // would otherwise look across the whole image).
    double maxPixels = 64.0;
    // ao.angle_bias: hbao's tangent angle bias, degrees, 0..60 (Bavoil & Sainz: samples within
    // it above the tangent plane count nothing, against a coarse surface's false occlusion).
    double angleBiasDeg = 20.0;
    // ao.gtao_angle_bias: gtao's, degrees, 0..60: horizons within it above the tangent plane
    // count nothing, and higher ones are lowered by it. 10 by default: the ambient_occlusion
    // study measures it within the bound on false occlusion on each of its scenes.
    double gtaoAngleBiasDeg = 10.0;
    // ao.thickness: the depth of each occluder behind the front the depth buffer holds, in
    // particle radii (the impostor's radius where it is seen), 0..1000; 0: without end, every
    // occluder a wall reaching back from its front (the methods as published). Against false
    // occlusion across a gap: the front of a body hanging over another.
    double thickness = 0.0;
    // ao.depth: "shaded" | "filtered". The impostors' bumps in the depth count as occluders
    // (docs/lighting.md); a filtered depth has none. Filtered by default: the ambient_occlusion
    // study measures it better than the shaded depth on each of its scenes for each method.
    AoDepth depth = AoDepth::Filtered;
    // ao.layers: 1 | 2. With 2, a second depth layer, the back of the body seen at each pixel
    // (each impostor's far side, where its body is the one in front), drawn for the occlusion
    // pass, gives each occluder its back: a body hanging over another no longer stands for a
    // wall down to it. With a thickness as well, the nearer of the two backs.
    int layers = 1;
    bool operator==(const AoSettings&) const = default;
};

// emissive.*: the real-time estimate of the light that emitting surfaces cast on the others,
// the irradiance E the shading adds as albedo E / pi (realtime/emissive_pass.cpp). It runs only
// under the scene's light.emissive_light, which the reference integrates exactly.
enum class EmissiveMethod {
    None,         // "none": no estimate; E = 0 even under light.emissive_light
    PointLights,  // "point_lights": each emitting body a point source at its centre, unshadowed
    Ssem,         // "ssem": screen-space emissive, rays marched against the depth buffer
    // "ssem_target": the same rays marched against a target of the emitting bodies alone, drawn
    // from the camera with a wider field of view (emissive.target_fov_scale): an emitter beside
    // the view still lights what is in view; occluders that do not emit cast no shadow.
    SsemTarget,
};
enum class EmissiveBlur {
    None,        // "none": the raw, noisy estimate
    DepthAware,  // "depth_aware": ao_blur.frag's Gaussian within a body and its depth
};
struct EmissiveSettings {
    // emissive.method: "none" | "point_lights" | "ssem" | "ssem_target". The point lights are the
    // cheap baseline: the screen-space rays see occluders but not what lies off screen.
    EmissiveMethod method = EmissiveMethod::PointLights;
    int directions = 16;  // emissive.directions: "ssem" cosine-weighted rays per pixel, 1..64
    int steps = 8;        // emissive.steps: "ssem" samples along each ray, 1..64
    // emissive.max_pixels: "ssem" a ray's reach, the world length that spans this many pixels
    // at the receiver's depth, cut to this many pixels on screen and at the near plane, 4..4096.
    double maxPixels = 256.0;
    // emissive.thickness: "ssem" how far a sample may lie behind the depth buffer and still meet
    // the surface there, in radii of the particle drawn at that pixel (so the same at every
    // scale and distance), (0, 1000]. Deeper, it passed behind a body and marches on. An
    // emitter is a whole body, not a shell: on the heated scene 16 brings the mean irradiance
    // on the cold body to 1.19 times the reference's, 4 to 0.47 (realtime/README.md).
    double thickness = 16.0;
    // emissive.blur: "none" | "depth_aware"; emissive.blur_radius: pixels, 1..16.
    EmissiveBlur blur = EmissiveBlur::DepthAware;
    int blurRadius = 4;
    // emissive.target_fov_scale: "ssem_target" the emitter target's field of view against the
    // camera's, tan(fov' / 2) = scale tan(fov / 2), 1..8; 2 sees as far beside the view again
    // as the view's own half-width.
    double targetFovScale = 2.0;
    // emissive.target_aspect: "ssem_target" true: the target keeps the camera's aspect and
    // resolution; false: a square target of the camera's height (the same vertical field of
    // view), to measure what the aspect correction brings.
    bool targetAspect = true;
    bool operator==(const EmissiveSettings&) const = default;
};

// atmosphere.*: where the real-time atmosphere pass ends each view ray in a body's atmosphere
// (bodies[].atmosphere, core/atmosphere.h; realtime/atmosphere_pass.cpp). The reference ends
// it at the exact hit.
enum class AtmosphereEndPoint {
    Impostor,  // "impostor": the G-buffer's impostor depth, as drawn
    Filtered,  // "filtered": the depth the shade pass read (a depth filter's; else as drawn)
    Sphere,    // "sphere": the analytic inner sphere (another body's pixels: the filtered depth)
    Blend,     // "blend": the filtered depth nearer than blend_near, the sphere beyond blend_far,
               // mixed by distance between
};
struct AtmosphereSettings {
    // atmosphere.end_point: "impostor" | "filtered" | "sphere" | "blend". Filtered by default:
    // the surface the shade pass drew, which a particle body's relief follows; the analytic
    // sphere wins only where the level set is round (docs/light.md, the atmosphere study).
    AtmosphereEndPoint endPoint = AtmosphereEndPoint::Filtered;
    double blendNear = 2.0;  // atmosphere.blend_near: scene units from the camera, >= 0
    double blendFar = 4.0;   // atmosphere.blend_far: scene units, > blend_near
    int steps = 0;  // atmosphere.steps: quadrature steps, 0..256; 0: the scene's atmosphere.steps
    bool operator==(const AtmosphereSettings&) const = default;
};

struct Settings {
    DepthMode depth = DepthMode::Log;                   // depth: "log" | "standard" | "reversed"
    GBufferFormat gbufferFormat = GBufferFormat::Full;  // gbuffer.format: "full" | "compact"
    PerSetDevice perSet = PerSetDevice::Gpu;            // per_set: "gpu" | "cpu"
    // per_set_fallback: where the device failed the per-set self-check (Device::perSetCheck),
    // a frame asking for per_set = "gpu" runs the CPU's per-set work (true) or keeps the GPU's,
    // for whoever debugs it (false); either way the frame says so.
    bool perSetFallback = true;
    // shadows: "map" | "pcf" | "spheres" | "none" | "esm" | "vsm" | "evsm"
    ShadowMode shadows = ShadowMode::Map;
    ParticleSettings particles;
    ShadowMapSettings shadowMap;
    SurfaceSettings surface;
    SsssSettings ssss;
    BloomSettings bloom;
    AoSettings ao;
    EmissiveSettings emissive;
    AtmosphereSettings atmosphere;
};

// Whether the settings ask for the ambient occlusion pass (ao.method is not "none"); a frame
// runs it where the scene's light.ao_radius is above 0 too.
bool usesAmbientOcclusion(const Settings& settings);
// Whether it filters a depth of its own: ao.depth is "filtered" and the surface method filters
// none (ssss, none).
bool filtersOcclusionDepth(const Settings& settings);
// Whether the occlusion pass draws its second depth layer: ao.layers = 2 with a screen-space
// method (the traced rays meet the spheres themselves).
bool usesBackLayer(const AoSettings& settings);
// Whether the emissive pass runs: the scene asks for the light of emitting surfaces
// (light.emissive_light), something emits, and emissive.method is not "none".
bool usesEmissiveLight(const Settings& settings, bool emissiveLight, bool emits);
// Whether the halo pass runs: particles.halo_pixels is set, the impostors are spheres and
// something emits.
bool usesHalo(const Settings& settings, bool emits);
// Whether a surface method's pass replaces the normals by those of its depth: the G-buffer's,
// the gradient pass's or the field normals are then thrown away (and not computed).
enum class NormalRebuild {
    Never,      // it keeps the normals it is given (or smooths them: SSSS)
    Always,     // a depth filter: normals from the filtered depth
    WhenAsked,  // the user's shader: with surface.shader_normals
};
// What a surface method is and needs, in one place: its name, whether it runs as the "surface"
// pass (after the G-buffer, before shading), and whether it rebuilds normals.
struct SurfaceMethodInfo {
    SurfaceMethod method;
    std::string_view name;
    bool surfacePass;
    NormalRebuild rebuildsNormals;
};
const SurfaceMethodInfo& surfaceMethodInfo(SurfaceMethod method);

// Whether the settings smooth with SSSS (surface.method = "ssss", ssss.enabled and a radius).
bool usesSsss(const Settings& settings);
// Whether a depth filter or the user's shader runs (the "surface" pass).
bool usesSurfaceFilter(const Settings& settings);
// Whether the surface pass replaces the normals by those of its depth (a depth filter, or the
// user's shader with surface.shader_normals): the gradient pass's would be thrown away.
bool rebuildsNormals(const Settings& settings);
// Whether the gradient pass runs (and needs the kernels that reach the surface).
bool usesKernels(const Settings& settings);
// Whether small droplets may be drawn as ellipsoids (realtime/droplets.h).
bool mayHaveDroplets(const ParticleSettings& particles);
// Whether the shadow map is drawn (every mode but "spheres" and "none").
bool usesShadowMap(ShadowMode mode);
// Whether the depth map is turned into a filtered map ("esm", "vsm", "evsm").
bool usesFilteredShadowMap(ShadowMode mode);

// Reads every key of the table (the scene's [realtime] section with --set overrides applied)
// and then calls table.checkAllRead(): an unknown key, a wrong type or an out-of-range value
// throws core::InputError naming the file, line and key.
Settings parseSettings(const core::ParameterTable& table);

// Every setting by dotted key ("realtime.ssss.enabled"), for the frame's JSON.
nlohmann::json toJson(const Settings& settings);

std::string_view toString(DepthMode mode);
std::string_view toString(GBufferFormat format);
std::string_view toString(ShadowMode mode);
std::string_view toString(EsmForm form);
std::string_view toString(NormalModel model);
std::string_view toString(RadiusModel model);
std::string_view toString(SurfaceMethod method);
std::string_view toString(ParticleShape shape);
std::string_view toString(EllipsoidAnchor anchor);
std::string_view toString(PerSetDevice device);
std::string_view toString(AoMethod method);
std::string_view toString(AoBlur blur);
std::string_view toString(AoNoise noise);
std::string_view toString(AoDepth depth);
std::string_view toString(EmissiveMethod method);
std::string_view toString(EmissiveBlur blur);
std::string_view toString(AtmosphereEndPoint endPoint);

}  // namespace twinrender::realtime
