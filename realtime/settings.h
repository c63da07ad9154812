// Settings of the real-time renderer: the [realtime] table of a scene (and --set realtime.*),
// read in exactly one place, parseSettings(). Keys are the dotted names in the comments.
#pragma once

#include <nlohmann/json.hpp>
#include <string_view>

#include "core/parameters.h"

namespace twinrender::realtime {

// How the depth buffer stores depth (DESIGN.md, "Depth"). The Z channel of the frame is
// linear eye depth in every mode.
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
};

// What normal the G-buffer writes per fragment (particles.normal).
enum class NormalModel {
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
    // crossing along the normal (at most radius_scale * h), [1, 4]. The crossing along the
    // normal is the nearest the level set comes on that side; between particles the smooth
    // level set bulges beyond the union of such spheres. Coverage IoU on the LAMMPS splash
    // frames 0/12/20/40: 0.979/0.912/0.905/0.900 at 1, 0.979/0.932/0.933/0.920 at 1.15,
    // 0.975/0.936/0.935/0.911 at 1.25, 0.970/0.934/0.927/0.897 at 1.35 (docs/methods.md).
    double crossingScale = 1.2;
    // particles.normal: "field" | "blend". The particle normal (the colour-field gradient at
    // the centre) is one direction per particle, while the rendered surface turns across a
    // particle; "field" follows the field's gradient over the impostor to first order: mean
    // normal error on the planet 2.9 degrees without SSSS, against 5.4 for "blend" (README).
    NormalModel normal = NormalModel::Gradient;
    // particles.sphere_normal_weight ("blend" only): the G-buffer normal is
    // normalize(mix(particle normal, impostor sphere normal, weight)), 0..1. At a surface point
    // the particle's own kernel adds a term along the sphere normal. 0.25 minimises the normal
    // error against the raymarcher (README).
    double sphereNormalWeight = 0.25;
    // particles.cull_hidden: skip particles whose impostor lies inside the union of its
    // neighbours' (realtime/occlusion_culling.h); the image does not change, only the cost.
    bool cullHidden = true;
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
};

struct SsssSettings {
    bool enabled = true;  // ssss.enabled: Screen-Space Surface Smoothing of uv, normal, emission
    // ssss.radius_scale: blur radius / projected particle radius, 0..16 (0 = no blur). Larger
    // hides more of the particles in uv (texture), smaller keeps the surface's real ripples in
    // the normals. 0.6 gave the lowest mean normal error against the raymarcher on the default
    // scenes (planet, field normal: 2.31 degrees; 2.31 at 0.4, 2.82 at 0.8, 3.50 at 1.0, 2.94
    // with SSSS off) at the same FLIP and uv error (README).
    double radiusScale = 0.6;
    // ssss.depth_limit: largest eye-depth difference between blurred pixels, in radii of the
    // centre pixel's particle, (0, 1000].
    double depthLimit = 3.0;
    int iterations = 1;     // ssss.iterations: the filter applied this many times, 1..16
    bool separable = true;  // ssss.separable: horizontal then vertical; false: the full 2-D kernel
    // ssss.max_taps: samples on each side of the centre (per axis in 2-D), 1..64; wider radii
    // are sampled every radius / max_taps pixels. 4 costs half of 8 for 0.05 deg of normal error.
    int maxTaps = 4;
};

struct BloomSettings {
    bool enabled = true;     // bloom.enabled: bloom in the PNG (never in the EXR)
    double strength = 0.05;  // bloom.strength: weight of the bloom added to the beauty, 0..10
    double threshold = 1.0;  // bloom.threshold: linear radiance above which pixels bloom, >= 0
};

struct Settings {
    DepthMode depth = DepthMode::Log;      // depth: "log" | "standard" | "reversed"
    ShadowMode shadows = ShadowMode::Map;  // shadows: "map" | "pcf" | "spheres" | "none"
    ParticleSettings particles;
    ShadowMapSettings shadowMap;
    SsssSettings ssss;
    BloomSettings bloom;
};

// Reads every key of the table (the scene's [realtime] section with --set overrides applied)
// and then calls table.checkAllRead(): an unknown key, a wrong type or an out-of-range value
// throws core::InputError naming the file, line and key.
Settings parseSettings(const core::ParameterTable& table);

// Every setting by dotted key ("realtime.ssss.enabled"), for the frame's JSON.
nlohmann::json toJson(const Settings& settings);

std::string_view toString(DepthMode mode);
std::string_view toString(ShadowMode mode);
std::string_view toString(NormalModel model);
std::string_view toString(RadiusModel model);

}  // namespace twinrender::realtime
