#include "realtime/settings.h"

#include <fmt/format.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "core/error.h"

namespace twinrender::realtime {

namespace {

DepthMode parseDepthMode(const std::string& s) {
    if (s == "standard") return DepthMode::Standard;
    if (s == "reversed") return DepthMode::Reversed;
    return DepthMode::Log;
}

ShadowMode parseShadowMode(const std::string& s) {
    if (s == "none") return ShadowMode::None;
    if (s == "pcf") return ShadowMode::Pcf;
    if (s == "spheres") return ShadowMode::Spheres;
    if (s == "esm") return ShadowMode::Esm;
    if (s == "vsm") return ShadowMode::Vsm;
    if (s == "evsm") return ShadowMode::Evsm;
    return ShadowMode::Map;
}

// The value of `values` whose name (toString) the key holds.
template <typename Enum, std::size_t N>
Enum byName(const std::string& name, const std::array<Enum, N>& values) {
    for (Enum v : values)
        if (toString(v) == name) return v;
    return values[0];
}

AoSettings parseAo(const core::ParameterTable& t) {
    const AoSettings d;
    AoSettings a;
    a.method = byName(t.getEnum("ao.method", std::string(toString(d.method)),
                                {"none", "ssao", "hbao", "gtao", "traced"}),
                      std::array{AoMethod::None, AoMethod::Ssao, AoMethod::Hbao, AoMethod::Gtao,
                                 AoMethod::Traced});
    a.slices = static_cast<int>(t.getInt("ao.slices", d.slices, 1, 32));
    a.steps = static_cast<int>(t.getInt("ao.steps", d.steps, 1, 64));
    a.rays = static_cast<int>(t.getInt("ao.rays", d.rays, 1, 256));
    a.blur =
        byName(t.getEnum("ao.blur", std::string(toString(d.blur)), {"none", "flat", "depth_aware"}),
               std::array{AoBlur::None, AoBlur::Flat, AoBlur::DepthAware});
    a.blurRadius = static_cast<int>(t.getInt("ao.blur_radius", d.blurRadius, 1, 16));
    a.noise = byName(t.getEnum("ao.noise", std::string(toString(d.noise)),
                               {"white", "interleaved_gradient", "blue"}),
                     std::array{AoNoise::White, AoNoise::InterleavedGradient, AoNoise::Blue});
    a.maxPixels = t.getDouble("ao.max_pixels", d.maxPixels, 4.0, 4096.0);
    a.angleBiasDeg = t.getDouble("ao.angle_bias", d.angleBiasDeg, 0.0, 60.0);
    a.gtaoAngleBiasDeg = t.getDouble("ao.gtao_angle_bias", d.gtaoAngleBiasDeg, 0.0, 60.0);
    a.thickness = t.getDouble("ao.thickness", d.thickness, 0.0, 1000.0);
    a.depth = byName(t.getEnum("ao.depth", std::string(toString(d.depth)), {"shaded", "filtered"}),
                     std::array{AoDepth::Shaded, AoDepth::Filtered});
    a.layers = static_cast<int>(t.getInt("ao.layers", d.layers, 1, 2));
    return a;
}

AtmosphereSettings parseAtmosphere(const core::ParameterTable& t) {
    const AtmosphereSettings d;
    AtmosphereSettings a;
    a.endPoint = byName(t.getEnum("atmosphere.end_point", std::string(toString(d.endPoint)),
                                  {"impostor", "filtered", "sphere", "blend"}),
                        std::array{AtmosphereEndPoint::Impostor, AtmosphereEndPoint::Filtered,
                                   AtmosphereEndPoint::Sphere, AtmosphereEndPoint::Blend});
    a.blendNear = t.getDouble("atmosphere.blend_near", d.blendNear, 0.0, 1e15);
    a.blendFar = t.getDouble("atmosphere.blend_far", d.blendFar, 0.0, 1e15);
    if (!(a.blendFar > a.blendNear))
        throw core::InputError(fmt::format("{} must be larger than atmosphere.blend_near ({})",
                                           t.describe("atmosphere.blend_far"), a.blendNear));
    a.steps = static_cast<int>(t.getInt("atmosphere.steps", d.steps, 0, 256));
    return a;
}

EmissiveSettings parseEmissive(const core::ParameterTable& t) {
    const EmissiveSettings d;
    EmissiveSettings e;
    e.method = byName(t.getEnum("emissive.method", std::string(toString(d.method)),
                                {"none", "point_lights", "ssem", "ssem_target"}),
                      std::array{EmissiveMethod::None, EmissiveMethod::PointLights,
                                 EmissiveMethod::Ssem, EmissiveMethod::SsemTarget});
    e.directions = static_cast<int>(t.getInt("emissive.directions", d.directions, 1, 64));
    e.steps = static_cast<int>(t.getInt("emissive.steps", d.steps, 1, 64));
    e.maxPixels = t.getDouble("emissive.max_pixels", d.maxPixels, 4.0, 4096.0);
    e.thickness = t.getDouble("emissive.thickness", d.thickness, 1e-6, 1000.0);
    e.blur =
        byName(t.getEnum("emissive.blur", std::string(toString(d.blur)), {"none", "depth_aware"}),
               std::array{EmissiveBlur::None, EmissiveBlur::DepthAware});
    e.blurRadius = static_cast<int>(t.getInt("emissive.blur_radius", d.blurRadius, 1, 16));
    e.targetFovScale = t.getDouble("emissive.target_fov_scale", d.targetFovScale, 1.0, 8.0);
    e.targetAspect = t.getBool("emissive.target_aspect", d.targetAspect);
    return e;
}

}  // namespace

std::string_view toString(AoMethod method) {
    switch (method) {
        case AoMethod::None:
            return "none";
        case AoMethod::Ssao:
            return "ssao";
        case AoMethod::Hbao:
            return "hbao";
        case AoMethod::Gtao:
            return "gtao";
        case AoMethod::Traced:
            return "traced";
    }
    return "none";
}

std::string_view toString(AoBlur blur) {
    switch (blur) {
        case AoBlur::None:
            return "none";
        case AoBlur::Flat:
            return "flat";
        case AoBlur::DepthAware:
            return "depth_aware";
    }
    return "depth_aware";
}

std::string_view toString(AoDepth depth) {
    return depth == AoDepth::Filtered ? "filtered" : "shaded";
}

std::string_view toString(AoNoise noise) {
    switch (noise) {
        case AoNoise::White:
            return "white";
        case AoNoise::InterleavedGradient:
            return "interleaved_gradient";
        case AoNoise::Blue:
            return "blue";
    }
    return "interleaved_gradient";
}

bool usesAmbientOcclusion(const Settings& settings) {
    return settings.ao.method != AoMethod::None;
}

bool usesBackLayer(const AoSettings& settings) {
    return settings.layers == 2 && settings.method != AoMethod::Traced &&
           settings.method != AoMethod::None;
}

bool filtersOcclusionDepth(const Settings& settings) {
    return usesAmbientOcclusion(settings) && settings.ao.depth == AoDepth::Filtered &&
           (settings.surface.method == SurfaceMethod::Ssss ||
            settings.surface.method == SurfaceMethod::None);
}

std::string_view toString(EmissiveMethod method) {
    switch (method) {
        case EmissiveMethod::None:
            return "none";
        case EmissiveMethod::PointLights:
            return "point_lights";
        case EmissiveMethod::Ssem:
            return "ssem";
        case EmissiveMethod::SsemTarget:
            return "ssem_target";
    }
    return "point_lights";
}

std::string_view toString(EmissiveBlur blur) {
    switch (blur) {
        case EmissiveBlur::None:
            return "none";
        case EmissiveBlur::DepthAware:
            return "depth_aware";
    }
    return "depth_aware";
}

std::string_view toString(AtmosphereEndPoint endPoint) {
    switch (endPoint) {
        case AtmosphereEndPoint::Impostor:
            return "impostor";
        case AtmosphereEndPoint::Filtered:
            return "filtered";
        case AtmosphereEndPoint::Sphere:
            return "sphere";
        case AtmosphereEndPoint::Blend:
            return "blend";
    }
    return "filtered";
}

bool usesEmissiveLight(const Settings& settings, bool emissiveLight, bool emits) {
    return emissiveLight && emits && settings.emissive.method != EmissiveMethod::None;
}

bool usesHalo(const Settings& settings, bool emits) {
    return emits && settings.particles.haloPixels > 0.0 &&
           settings.particles.shape == ParticleShape::Sphere;
}

std::string_view toString(DepthMode mode) {
    switch (mode) {
        case DepthMode::Standard:
            return "standard";
        case DepthMode::Log:
            return "log";
        case DepthMode::Reversed:
            return "reversed";
    }
    return "log";
}

std::string_view toString(GBufferFormat format) {
    return format == GBufferFormat::Compact ? "compact" : "full";
}

std::string_view toString(ShadowMode mode) {
    switch (mode) {
        case ShadowMode::None:
            return "none";
        case ShadowMode::Map:
            return "map";
        case ShadowMode::Pcf:
            return "pcf";
        case ShadowMode::Spheres:
            return "spheres";
        case ShadowMode::Esm:
            return "esm";
        case ShadowMode::Vsm:
            return "vsm";
        case ShadowMode::Evsm:
            return "evsm";
    }
    return "map";
}

std::string_view toString(EsmForm form) {
    return form == EsmForm::Seed ? "seed" : "warp";
}

std::string_view toString(NormalModel model) {
    switch (model) {
        case NormalModel::Blend:
            return "blend";
        case NormalModel::Gradient:
            return "gradient";
        case NormalModel::Sphere:
            return "sphere";
        case NormalModel::Field:
            break;
    }
    return "field";
}

std::string_view toString(RadiusModel model) {
    return model == RadiusModel::Fixed ? "fixed" : "field";
}

std::string_view toString(ParticleShape shape) {
    return shape == ParticleShape::Ellipsoid ? "ellipsoid" : "sphere";
}

std::string_view toString(EllipsoidAnchor anchor) {
    return anchor == EllipsoidAnchor::Centre ? "centre" : "surface";
}

std::string_view toString(PerSetDevice device) {
    return device == PerSetDevice::Cpu ? "cpu" : "gpu";
}

namespace {

// Each surface method with its name and what it needs of the frame (surfaceMethodInfo).
constexpr SurfaceMethodInfo SURFACE_METHODS[] = {
    {.method = SurfaceMethod::Ssss,
     .name = "ssss",
     .surfacePass = false,
     .rebuildsNormals = NormalRebuild::Never},
    {.method = SurfaceMethod::Bilateral,
     .name = "bilateral",
     .surfacePass = true,
     .rebuildsNormals = NormalRebuild::Always},
    {.method = SurfaceMethod::NarrowRange,
     .name = "narrow_range",
     .surfacePass = true,
     .rebuildsNormals = NormalRebuild::Always},
    {.method = SurfaceMethod::CurvatureFlow,
     .name = "curvature_flow",
     .surfacePass = true,
     .rebuildsNormals = NormalRebuild::Always},
    {.method = SurfaceMethod::None,
     .name = "none",
     .surfacePass = false,
     .rebuildsNormals = NormalRebuild::Never},
    {.method = SurfaceMethod::Shader,
     .name = "shader",
     .surfacePass = true,
     .rebuildsNormals = NormalRebuild::WhenAsked},
};

// The surface.* keys: the method, the shader's text read (relative to the scene file), each
// filter's parameters.
SurfaceSettings parseSurface(const core::ParameterTable& t) {
    const SurfaceSettings d;
    SurfaceSettings s;
    const std::string shader = t.getString("surface.shader", "");
    const std::string method =
        t.getEnum("surface.method", shader.empty() ? std::string(toString(d.method)) : "shader",
                  {"ssss", "bilateral", "narrow_range", "curvature_flow", "none", "shader"});
    for (const SurfaceMethodInfo& m : SURFACE_METHODS)
        if (m.name == method) s.method = m.method;
    if (s.method == SurfaceMethod::Shader && shader.empty())
        throw core::InputError(fmt::format(
            "{}: surface.method = \"shader\" needs realtime.surface.shader = PATH (a GLSL file "
            "defining filterSurface; see realtime/shaders/user_surface.frag)",
            t.describe("surface.method")));
    if (!shader.empty() && s.method != SurfaceMethod::Shader)
        throw core::InputError(
            fmt::format("{}: realtime.surface.shader is given but surface.method is \"{}\"; set "
                        "surface.method = \"shader\" or leave it out",
                        t.describe("surface.shader"), method));
    if (!shader.empty()) {
        std::filesystem::path path(shader);
        // Relative to the scene file, as its other paths; an override's to the working folder.
        const bool fromOverride = t.find("surface.shader")->where.starts_with("--set");
        if (path.is_relative() && !t.file().empty() && !fromOverride)
            path = std::filesystem::path(t.file()).parent_path() / path;
        std::ifstream in(path, std::ios::binary);
        if (!in)
            throw core::InputError(fmt::format("{}: cannot read the shader file '{}'",
                                               t.describe("surface.shader"), path.string()));
        std::ostringstream text;
        text << in.rdbuf();
        s.shaderPath = path.string();
        s.shaderSource = text.str();
    }
    s.shaderPasses = static_cast<int>(t.getInt("surface.shader_passes", d.shaderPasses, 1, 64));
    s.shaderNormals = t.getBool("surface.shader_normals", d.shaderNormals);

    const BilateralSettings& db = d.bilateral;
    BilateralSettings& b = s.bilateral;
    b.radius = t.getDouble("surface.bilateral.radius", db.radius, 1e-6, 16.0);
    b.depthSigma = t.getDouble("surface.bilateral.depth_sigma", db.depthSigma, 1e-6, 1000.0);
    b.iterations = static_cast<int>(t.getInt("surface.bilateral.iterations", db.iterations, 1, 16));
    b.separable = t.getBool("surface.bilateral.separable", db.separable);
    b.maxRadiusPx = t.getDouble("surface.bilateral.max_radius_px", db.maxRadiusPx, 1.0, 64.0);

    const NarrowRangeSettings& dn = d.narrowRange;
    NarrowRangeSettings& n = s.narrowRange;
    n.radius = t.getDouble("surface.narrow_range.radius", dn.radius, 1e-6, 16.0);
    n.threshold = t.getDouble("surface.narrow_range.threshold", dn.threshold, 1e-6, 1000.0);
    n.clamp = t.getDouble("surface.narrow_range.clamp", dn.clamp, 0.0, 1000.0);
    n.iterations =
        static_cast<int>(t.getInt("surface.narrow_range.iterations", dn.iterations, 1, 16));
    n.separable = t.getBool("surface.narrow_range.separable", dn.separable);
    n.maxRadiusPx = t.getDouble("surface.narrow_range.max_radius_px", dn.maxRadiusPx, 1.0, 256.0);

    const CurvatureFlowSettings& dc = d.curvatureFlow;
    CurvatureFlowSettings& c = s.curvatureFlow;
    c.iterations =
        static_cast<int>(t.getInt("surface.curvature_flow.iterations", dc.iterations, 0, 500));
    c.timeStep = t.getDouble("surface.curvature_flow.time_step", dc.timeStep, 1e-6, 0.25);
    c.depthLimit = t.getDouble("surface.curvature_flow.depth_limit", dc.depthLimit, 1e-6, 1000.0);
    return s;
}

}  // namespace

const SurfaceMethodInfo& surfaceMethodInfo(SurfaceMethod method) {
    for (const SurfaceMethodInfo& m : SURFACE_METHODS)
        if (m.method == method) return m;
    return SURFACE_METHODS[0];
}

std::string_view toString(SurfaceMethod method) {
    return surfaceMethodInfo(method).name;
}

bool usesSsss(const Settings& s) {
    return s.surface.method == SurfaceMethod::Ssss && s.ssss.enabled && s.ssss.radiusScale > 0.0;
}

bool usesSurfaceFilter(const Settings& s) {
    return surfaceMethodInfo(s.surface.method).surfacePass;
}

bool rebuildsNormals(const Settings& s) {
    switch (surfaceMethodInfo(s.surface.method).rebuildsNormals) {
        case NormalRebuild::Never:
            return false;
        case NormalRebuild::Always:
            return true;
        case NormalRebuild::WhenAsked:
            return s.surface.shaderNormals;
    }
    return false;
}

bool usesKernels(const Settings& s) {
    return s.particles.normal == NormalModel::Gradient && !rebuildsNormals(s);
}

bool mayHaveDroplets(const ParticleSettings& p) {
    return p.radius == RadiusModel::Field && p.dropletAtoms >= 2;
}

bool usesShadowMap(ShadowMode mode) {
    return mode != ShadowMode::None && mode != ShadowMode::Spheres;
}

bool usesFilteredShadowMap(ShadowMode mode) {
    return mode == ShadowMode::Esm || mode == ShadowMode::Vsm || mode == ShadowMode::Evsm;
}

Settings parseSettings(const core::ParameterTable& t) {
    const Settings d;  // defaults
    Settings s;
    s.depth = parseDepthMode(
        t.getEnum("depth", std::string(toString(d.depth)), {"log", "standard", "reversed"}));
    s.gbufferFormat = t.getEnum("gbuffer.format", std::string(toString(d.gbufferFormat)),
                                {"full", "compact"}) == "compact"
                          ? GBufferFormat::Compact
                          : GBufferFormat::Full;
    s.perSet = t.getEnum("per_set", std::string(toString(d.perSet)), {"gpu", "cpu"}) == "cpu"
                   ? PerSetDevice::Cpu
                   : PerSetDevice::Gpu;
    s.perSetFallback = t.getBool("per_set_fallback", d.perSetFallback);
    s.shadows = parseShadowMode(t.getEnum("shadows", std::string(toString(d.shadows)),
                                          {"map", "pcf", "spheres", "none", "esm", "vsm", "evsm"}));
    s.particles.radiusScale =
        t.getDouble("particles.radius_scale", d.particles.radiusScale, 1e-6, 10.0);
    s.particles.radius = t.getEnum("particles.radius", std::string(toString(d.particles.radius)),
                                   {"field", "fixed"}) == "fixed"
                             ? RadiusModel::Fixed
                             : RadiusModel::Field;
    s.particles.crossingScale =
        t.getDouble("particles.crossing_scale", d.particles.crossingScale, 1.0, 4.0);
    s.particles.interiorLevel =
        t.getDouble("particles.interior_level", d.particles.interiorLevel, 1e-6, 1e6);
    s.particles.dropletAtoms =
        static_cast<int>(t.getInt("particles.droplet_atoms", d.particles.dropletAtoms, 0, 64));
    s.particles.surfaceLevel =
        t.getDouble("particles.surface_level", d.particles.surfaceLevel, 1e-6, 1e6);
    const std::string normal =
        t.getEnum("particles.normal", std::string(toString(d.particles.normal)),
                  {"field", "blend", "gradient", "sphere"});
    s.particles.normal = normal == "blend"      ? NormalModel::Blend
                         : normal == "gradient" ? NormalModel::Gradient
                         : normal == "sphere"   ? NormalModel::Sphere
                                                : NormalModel::Field;
    s.particles.sphereNormalWeight =
        t.getDouble("particles.sphere_normal_weight", d.particles.sphereNormalWeight, 0.0, 1.0);
    s.particles.cullHidden = t.getBool("particles.cull_hidden", d.particles.cullHidden);
    s.particles.minPixels = t.getDouble("particles.min_pixels", d.particles.minPixels, 0.0, 64.0);
    s.particles.haloPixels =
        t.getDouble("particles.halo_pixels", d.particles.haloPixels, 0.0, 64.0);
    if (s.particles.minPixels > 0.0 && s.particles.haloPixels > 0.0)
        throw core::InputError(fmt::format(
            "{}: particles.halo_pixels and particles.min_pixels are two ways to draw a sub-pixel "
            "emitter; set one of them (the other 0)",
            t.describe("particles.halo_pixels")));
    s.particles.bodySpherePixels =
        t.getDouble("particles.body_sphere_pixels", d.particles.bodySpherePixels, 0.0, 4096.0);
    s.particles.shape = t.getEnum("particles.shape", std::string(toString(d.particles.shape)),
                                  {"sphere", "ellipsoid"}) == "ellipsoid"
                            ? ParticleShape::Ellipsoid
                            : ParticleShape::Sphere;
    const AnisotropySettings& da = d.particles.anisotropy;
    AnisotropySettings& a = s.particles.anisotropy;
    a.smoothing = t.getDouble("particles.anisotropy.smoothing", da.smoothing, 0.0, 1.0);
    a.maxAxisRatio = t.getDouble("particles.anisotropy.max_axis_ratio", da.maxAxisRatio, 1.0, 16.0);
    a.minNeighbours = static_cast<int>(
        t.getInt("particles.anisotropy.min_neighbours", da.minNeighbours, 1, 1000));
    a.anchor = t.getEnum("particles.anisotropy.anchor", std::string(toString(da.anchor)),
                         {"surface", "centre"}) == "centre"
                   ? EllipsoidAnchor::Centre
                   : EllipsoidAnchor::Surface;

    s.shadowMap.resolution =
        static_cast<int>(t.getInt("shadow_map.resolution", d.shadowMap.resolution, 16, 16384));
    s.shadowMap.bias = t.getDouble("shadow_map.bias", d.shadowMap.bias, 0.0, 10.0);
    s.shadowMap.slopeBias = t.getDouble("shadow_map.slope_bias", d.shadowMap.slopeBias, 0.0, 100.0);
    s.shadowMap.pcfRadius = t.getDouble("shadow_map.pcf_radius", d.shadowMap.pcfRadius, 0.0, 16.0);
    s.shadowMap.blurRadius =
        t.getDouble("shadow_map.blur_radius", d.shadowMap.blurRadius, 0.0, 16.0);
    s.shadowMap.esmExponent =
        t.getDouble("shadow_map.esm_exponent", d.shadowMap.esmExponent, 0.0, 80.0);
    s.shadowMap.esmForm =
        t.getEnum("shadow_map.esm_form", std::string(toString(d.shadowMap.esmForm)),
                  {"seed", "warp"}) == "seed"
            ? EsmForm::Seed
            : EsmForm::Warp;
    s.shadowMap.vsmBleedReduction =
        t.getDouble("shadow_map.vsm_bleed_reduction", d.shadowMap.vsmBleedReduction, 0.0, 0.99);
    s.shadowMap.evsmPositiveExponent = t.getDouble("shadow_map.evsm_positive_exponent",
                                                   d.shadowMap.evsmPositiveExponent, 0.0, 42.0);
    s.shadowMap.evsmNegativeExponent = t.getDouble("shadow_map.evsm_negative_exponent",
                                                   d.shadowMap.evsmNegativeExponent, 0.0, 42.0);

    s.surface = parseSurface(t);
    s.ao = parseAo(t);
    s.emissive = parseEmissive(t);
    s.atmosphere = parseAtmosphere(t);
    s.ssss.enabled = t.getBool("ssss.enabled", d.ssss.enabled);
    s.ssss.radiusScale = t.getDouble("ssss.radius_scale", d.ssss.radiusScale, 0.0, 16.0);
    s.ssss.depthLimit = t.getDouble("ssss.depth_limit", d.ssss.depthLimit, 1e-6, 1000.0);
    s.ssss.iterations = static_cast<int>(t.getInt("ssss.iterations", d.ssss.iterations, 1, 16));
    s.ssss.separable = t.getBool("ssss.separable", d.ssss.separable);
    s.ssss.maxTaps = static_cast<int>(t.getInt("ssss.max_taps", d.ssss.maxTaps, 1, 64));

    s.bloom.enabled = t.getBool("bloom.enabled", d.bloom.enabled);
    s.bloom.strength = t.getDouble("bloom.strength", d.bloom.strength, 0.0, 10.0);
    s.bloom.threshold = t.getDouble("bloom.threshold", d.bloom.threshold, 0.0, 1e30);

    t.checkAllRead();
    return s;
}

nlohmann::json toJson(const Settings& s) {
    return {
        {"realtime.depth", toString(s.depth)},
        {"realtime.gbuffer.format", toString(s.gbufferFormat)},
        {"realtime.shadows", toString(s.shadows)},
        {"realtime.per_set", toString(s.perSet)},
        {"realtime.per_set_fallback", s.perSetFallback},
        {"realtime.particles.radius_scale", s.particles.radiusScale},
        {"realtime.particles.radius", toString(s.particles.radius)},
        {"realtime.particles.surface_level", s.particles.surfaceLevel},
        {"realtime.particles.crossing_scale", s.particles.crossingScale},
        {"realtime.particles.interior_level", s.particles.interiorLevel},
        {"realtime.particles.droplet_atoms", s.particles.dropletAtoms},
        {"realtime.particles.normal", toString(s.particles.normal)},
        {"realtime.particles.sphere_normal_weight", s.particles.sphereNormalWeight},
        {"realtime.particles.cull_hidden", s.particles.cullHidden},
        {"realtime.particles.min_pixels", s.particles.minPixels},
        {"realtime.particles.halo_pixels", s.particles.haloPixels},
        {"realtime.particles.body_sphere_pixels", s.particles.bodySpherePixels},
        {"realtime.particles.shape", toString(s.particles.shape)},
        {"realtime.particles.anisotropy.smoothing", s.particles.anisotropy.smoothing},
        {"realtime.particles.anisotropy.max_axis_ratio", s.particles.anisotropy.maxAxisRatio},
        {"realtime.particles.anisotropy.min_neighbours", s.particles.anisotropy.minNeighbours},
        {"realtime.particles.anisotropy.anchor", toString(s.particles.anisotropy.anchor)},
        {"realtime.shadow_map.resolution", s.shadowMap.resolution},
        {"realtime.shadow_map.bias", s.shadowMap.bias},
        {"realtime.shadow_map.slope_bias", s.shadowMap.slopeBias},
        {"realtime.shadow_map.pcf_radius", s.shadowMap.pcfRadius},
        {"realtime.shadow_map.blur_radius", s.shadowMap.blurRadius},
        {"realtime.shadow_map.esm_exponent", s.shadowMap.esmExponent},
        {"realtime.shadow_map.esm_form", toString(s.shadowMap.esmForm)},
        {"realtime.shadow_map.vsm_bleed_reduction", s.shadowMap.vsmBleedReduction},
        {"realtime.shadow_map.evsm_positive_exponent", s.shadowMap.evsmPositiveExponent},
        {"realtime.shadow_map.evsm_negative_exponent", s.shadowMap.evsmNegativeExponent},
        {"realtime.ao.method", toString(s.ao.method)},
        {"realtime.ao.slices", s.ao.slices},
        {"realtime.ao.steps", s.ao.steps},
        {"realtime.ao.rays", s.ao.rays},
        {"realtime.ao.blur", toString(s.ao.blur)},
        {"realtime.ao.blur_radius", s.ao.blurRadius},
        {"realtime.ao.noise", toString(s.ao.noise)},
        {"realtime.ao.max_pixels", s.ao.maxPixels},
        {"realtime.ao.angle_bias", s.ao.angleBiasDeg},
        {"realtime.ao.gtao_angle_bias", s.ao.gtaoAngleBiasDeg},
        {"realtime.ao.thickness", s.ao.thickness},
        {"realtime.ao.depth", toString(s.ao.depth)},
        {"realtime.ao.layers", s.ao.layers},
        {"realtime.emissive.method", toString(s.emissive.method)},
        {"realtime.emissive.directions", s.emissive.directions},
        {"realtime.emissive.steps", s.emissive.steps},
        {"realtime.emissive.max_pixels", s.emissive.maxPixels},
        {"realtime.emissive.thickness", s.emissive.thickness},
        {"realtime.emissive.blur", toString(s.emissive.blur)},
        {"realtime.emissive.blur_radius", s.emissive.blurRadius},
        {"realtime.emissive.target_fov_scale", s.emissive.targetFovScale},
        {"realtime.emissive.target_aspect", s.emissive.targetAspect},
        {"realtime.atmosphere.end_point", toString(s.atmosphere.endPoint)},
        {"realtime.atmosphere.blend_near", s.atmosphere.blendNear},
        {"realtime.atmosphere.blend_far", s.atmosphere.blendFar},
        {"realtime.atmosphere.steps", s.atmosphere.steps},
        {"realtime.surface.method", toString(s.surface.method)},
        {"realtime.surface.shader", s.surface.shaderPath},
        {"realtime.surface.shader_passes", s.surface.shaderPasses},
        {"realtime.surface.shader_normals", s.surface.shaderNormals},
        {"realtime.surface.bilateral.radius", s.surface.bilateral.radius},
        {"realtime.surface.bilateral.depth_sigma", s.surface.bilateral.depthSigma},
        {"realtime.surface.bilateral.iterations", s.surface.bilateral.iterations},
        {"realtime.surface.bilateral.separable", s.surface.bilateral.separable},
        {"realtime.surface.bilateral.max_radius_px", s.surface.bilateral.maxRadiusPx},
        {"realtime.surface.narrow_range.radius", s.surface.narrowRange.radius},
        {"realtime.surface.narrow_range.threshold", s.surface.narrowRange.threshold},
        {"realtime.surface.narrow_range.clamp", s.surface.narrowRange.clamp},
        {"realtime.surface.narrow_range.iterations", s.surface.narrowRange.iterations},
        {"realtime.surface.narrow_range.separable", s.surface.narrowRange.separable},
        {"realtime.surface.narrow_range.max_radius_px", s.surface.narrowRange.maxRadiusPx},
        {"realtime.surface.curvature_flow.iterations", s.surface.curvatureFlow.iterations},
        {"realtime.surface.curvature_flow.time_step", s.surface.curvatureFlow.timeStep},
        {"realtime.surface.curvature_flow.depth_limit", s.surface.curvatureFlow.depthLimit},
        {"realtime.ssss.enabled", s.ssss.enabled},
        {"realtime.ssss.radius_scale", s.ssss.radiusScale},
        {"realtime.ssss.depth_limit", s.ssss.depthLimit},
        {"realtime.ssss.iterations", s.ssss.iterations},
        {"realtime.ssss.separable", s.ssss.separable},
        {"realtime.ssss.max_taps", s.ssss.maxTaps},
        {"realtime.bloom.enabled", s.bloom.enabled},
        {"realtime.bloom.strength", s.bloom.strength},
        {"realtime.bloom.threshold", s.bloom.threshold},
    };
}

}  // namespace twinrender::realtime
