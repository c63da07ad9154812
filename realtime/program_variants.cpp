#include "realtime/program_variants.h"

#include <map>
#include <utility>

#include "realtime/gl/error.h"
#include "realtime/passes.h"
#include "realtime/per_set_gpu.h"

namespace twinrender::realtime {

ProgramVariant ProgramVariant::draw(std::string vertex, std::string fragment,
                                    std::vector<std::string> defines) {
    ProgramVariant v;
    v.vertex = std::move(vertex);
    v.fragment = std::move(fragment);
    v.defines = std::move(defines);
    return v;
}

ProgramVariant ProgramVariant::computeProgram(std::string file, std::vector<std::string> defines) {
    ProgramVariant v;
    v.compute = std::move(file);
    v.defines = std::move(defines);
    return v;
}

ProgramVariant ProgramVariant::userSurface() {
    ProgramVariant v = draw("fullscreen.vert", "user_surface.frag");
    v.userShader = true;
    return v;
}

std::string ProgramVariant::name() const {
    return compute.empty() ? ProgramCache::drawName(vertex, fragment, defines)
                           : ProgramCache::computeName(compute, defines);
}

const gl::Program& ProgramVariant::build(ProgramCache& programs, const IncludedFile* user) const {
    if (!compute.empty()) return programs.compute(compute, defines);
    const IncludedFile fallback = passThroughSurfaceFilter();
    return programs.get(vertex, fragment, defines,
                        userShader ? (user ? user : &fallback) : nullptr);
}

IncludedFile passThroughSurfaceFilter() {
    return {"user_surface.glsl", "surface_pass_through.glsl",
            std::string(shaderFile("surface_pass_through.glsl"))};
}

namespace {

void surfaceVariants(const SurfaceSettings& s, std::vector<ProgramVariant>& out) {
    auto add = [&](const char* fragment, std::vector<std::string> defines = {}) {
        out.push_back(ProgramVariant::draw("fullscreen.vert", fragment, std::move(defines)));
    };
    switch (s.method) {
        case SurfaceMethod::Bilateral:
            add("bilateral.frag", s.bilateral.separable ? std::vector<std::string>{"SEPARABLE"}
                                                        : std::vector<std::string>{});
            break;
        case SurfaceMethod::NarrowRange:
            add("narrow_range.frag");
            if (s.narrowRange.separable) add("narrow_range.frag", {"SEPARABLE"});
            break;
        case SurfaceMethod::CurvatureFlow:
            add("curvature_flow.frag");
            break;
        case SurfaceMethod::Shader:
            out.push_back(ProgramVariant::userSurface());
            break;
        case SurfaceMethod::Ssss:
        case SurfaceMethod::None:
            return;
    }
    if (s.method != SurfaceMethod::Shader || s.shaderNormals) add("depth_normals.frag");
}

}  // namespace

std::vector<ProgramVariant> programVariants(const Settings& settings, bool emits,
                                            bool emissiveLight, bool atmosphere) {
    std::vector<ProgramVariant> out;
    auto add = [&](const char* vertex, const char* fragment, std::vector<std::string> defines) {
        out.push_back(ProgramVariant::draw(vertex, fragment, std::move(defines)));
    };
    // A set with droplets draws them with the ellipsoid programs, apart from the spheres.
    const bool anisotropic = settings.particles.shape == ParticleShape::Ellipsoid;
    // With per_set = "gpu", a frame that draws some body as one sphere draws the particles with
    // the BODY_MASK variants (SceneBuffers::bodyMask), one that draws none without.
    const bool bodySpheres = settings.particles.bodySpherePixels > 0.0;
    const bool bodyMask = bodySpheres && settings.perSet == PerSetDevice::Gpu;
    // ao.layers = 2: the occlusion pass's second depth layer, drawn with the G-buffer's shapes.
    const bool backLayer = usesAmbientOcclusion(settings) && usesBackLayer(settings.ao);
    for (const bool masked : {false, true}) {
        if (masked && !bodyMask) continue;
        for (const bool ellipsoids : {false, true}) {
            if (ellipsoids != anisotropic && !(ellipsoids && mayHaveDroplets(settings.particles)))
                continue;
            auto defines = [&](std::vector<std::string> d) {
                return impostorDefines(ellipsoids, bodyMaskDefines(masked, std::move(d)));
            };
            if (usesShadowMap(settings.shadows))
                add("impostor.vert", "shadow.frag", defines({"SHADOW_PASS"}));
            add("impostor.vert", "gbuffer.frag", defines({depthDefine(settings.depth)}));
            if (backLayer)
                add("impostor.vert", "gbuffer.frag", defines(backLayerDefines(settings.depth)));
            if (emissiveLight && settings.emissive.method == EmissiveMethod::SsemTarget)
                add("impostor.vert", "gbuffer.frag", defines(emitterTargetDefines(settings.depth)));
        }
    }
    // Bodies drawn as one sphere each (particles.body_sphere_pixels), after the particles.
    if (bodySpheres) {
        if (usesShadowMap(settings.shadows))
            add("impostor.vert", "shadow.frag", bodySphereDefines({"SHADOW_PASS"}));
        add("impostor.vert", "gbuffer.frag", bodySphereDefines({depthDefine(settings.depth)}));
        if (backLayer)
            add("impostor.vert", "gbuffer.frag",
                bodySphereDefines(backLayerDefines(settings.depth)));
        if (emissiveLight && settings.emissive.method == EmissiveMethod::SsemTarget)
            add("impostor.vert", "gbuffer.frag",
                bodySphereDefines(emitterTargetDefines(settings.depth)));
    }
    if (settings.particles.normal == NormalModel::Gradient) {
        add("support.vert", "gradient_splat.frag", {depthDefine(settings.depth)});
        add("fullscreen.vert", "gradient_resolve.frag", {});
    }
    if (usesSsss(settings)) {
        std::vector<std::string> defines;
        if (settings.ssss.separable) defines.emplace_back("SEPARABLE");
        if (emits) defines.emplace_back("EMISSION");
        add("fullscreen.vert", "ssss.frag", defines);
    }
    if (usesSurfaceFilter(settings)) surfaceVariants(settings.surface, out);
    if (usesFilteredShadowMap(settings.shadows)) {
        add("fullscreen.vert", "shadow_moments.frag",
            shadowMomentsDefines(settings.shadows, settings.shadowMap));
        if (settings.shadowMap.blurRadius > 0.0) add("fullscreen.vert", "shadow_blur.frag", {});
    }
    if (filtersOcclusionDepth(settings)) {
        add("fullscreen.vert", "narrow_range.frag", {});
        if (settings.surface.narrowRange.separable)
            add("fullscreen.vert", "narrow_range.frag", {"SEPARABLE"});
        add("fullscreen.vert", "depth_normals.frag", {});
    }
    if (usesAmbientOcclusion(settings)) {
        add("fullscreen.vert",
            settings.ao.method == AoMethod::Traced ? "ao_traced.frag" : "ao.frag",
            ambientOcclusionDefines(settings.ao));
        if (settings.ao.blur != AoBlur::None)
            add("fullscreen.vert", "ao_blur.frag",
                settings.ao.blur == AoBlur::DepthAware ? std::vector<std::string>{"AO_DEPTH_AWARE"}
                                                       : std::vector<std::string>{});
    }
    if (emissiveLight)
        for (EmissiveProgram& p : emissivePrograms(settings.emissive))
            add("fullscreen.vert", p.fragment, std::move(p.defines));
    if (usesHalo(settings, emits)) {
        add("halo.vert", "halo.frag", {});
        if (bodyMask) add("halo.vert", "halo.frag", bodyMaskDefines(true, {}));
    }
    // With an occlusion method, a scene without light.ao_radius shades without it.
    add("fullscreen.vert", "shade.frag",
        shadeDefines(settings.shadows, settings.shadowMap, emits, false, emissiveLight));
    if (usesAmbientOcclusion(settings))
        add("fullscreen.vert", "shade.frag",
            shadeDefines(settings.shadows, settings.shadowMap, emits, true, emissiveLight));
    if (atmosphere)
        add("fullscreen.vert", "atmosphere.frag", atmosphereDefines(settings.atmosphere));
    // The bloom's levels exist where the image is large enough; the composite without them
    // either way.
    if (settings.bloom.enabled && settings.bloom.strength > 0.0) {
        add("fullscreen.vert", "bloom_bright.frag", {});
        add("fullscreen.vert", "bloom_down.frag", {});
        add("fullscreen.vert", "bloom_up.frag", {});
        add("fullscreen.vert", "composite.frag", {"BLOOM"});
    }
    add("fullscreen.vert", "composite.frag", {});
    if (settings.perSet == PerSetDevice::Gpu) {
        for (ProgramVariant& v : perSetPrograms(perSetRequest(settings)))
            out.push_back(std::move(v));
        if (settings.particles.normal == NormalModel::Gradient) {
            out.push_back(ProgramVariant::computeProgram("gradient_gather.comp", {}));
            if (bodyMask)
                for (std::vector<std::string> d :
                     {std::vector<std::string>{"BODY_MASK"}, {"BODY_MASK", "KERNEL_BODIES"}})
                    out.push_back(ProgramVariant::computeProgram("gradient_gather.comp", d));
        }
    }
    return out;
}

std::vector<ProgramVariant> allProgramVariants() {
    std::map<std::string, ProgramVariant> all;
    Settings s;
    for (DepthMode depth : {DepthMode::Standard, DepthMode::Log, DepthMode::Reversed})
        for (ShadowMode shadows :
             {ShadowMode::None, ShadowMode::Map, ShadowMode::Pcf, ShadowMode::Spheres,
              ShadowMode::Esm, ShadowMode::Vsm, ShadowMode::Evsm})
            for (ParticleShape shape : {ParticleShape::Sphere, ParticleShape::Ellipsoid})
                for (NormalModel normal : {NormalModel::Sphere, NormalModel::Field,
                                           NormalModel::Blend, NormalModel::Gradient})
                    for (RadiusModel radius : {RadiusModel::Field, RadiusModel::Fixed})
                        for (int atoms : {0, 8})
                            for (SurfaceMethod method :
                                 {SurfaceMethod::Ssss, SurfaceMethod::Bilateral,
                                  SurfaceMethod::NarrowRange, SurfaceMethod::CurvatureFlow,
                                  SurfaceMethod::None, SurfaceMethod::Shader})
                                // The flags each apply to one method: all on, then all off.
                                for (bool flags : {true, false})
                                    for (bool emits : {false, true})
                                        for (bool cull : {false, true})
                                            for (PerSetDevice where :
                                                 {PerSetDevice::Gpu, PerSetDevice::Cpu}) {
                                                s.depth = depth;
                                                s.shadows = shadows;
                                                s.particles.shape = shape;
                                                s.particles.normal = normal;
                                                s.particles.radius = radius;
                                                s.particles.dropletAtoms = atoms;
                                                s.particles.cullHidden = cull;
                                                s.surface.method = method;
                                                s.ssss.separable = flags;
                                                s.surface.bilateral.separable = flags;
                                                s.surface.narrowRange.separable = flags;
                                                s.surface.shaderNormals = flags;
                                                s.shadowMap.esmForm =
                                                    flags ? EsmForm::Warp : EsmForm::Seed;
                                                s.perSet = where;
                                                for (ProgramVariant& v : programVariants(s, emits))
                                                    all.try_emplace(v.name(), std::move(v));
                                            }
    // The ambient occlusion's programs, beside the defaults above.
    for (AoMethod method : {AoMethod::Ssao, AoMethod::Hbao, AoMethod::Gtao, AoMethod::Traced})
        for (AoNoise noise : {AoNoise::White, AoNoise::InterleavedGradient, AoNoise::Blue})
            for (AoBlur blur : {AoBlur::None, AoBlur::Flat, AoBlur::DepthAware})
                for (ShadowMode shadows : {ShadowMode::None, ShadowMode::Map})
                    for (bool emits : {false, true})
                        for (int layers : {1, 2}) {
                            Settings a;
                            a.ao.method = method;
                            a.ao.noise = noise;
                            a.ao.blur = blur;
                            a.ao.layers = layers;
                            a.shadows = shadows;
                            for (ProgramVariant& v : programVariants(a, emits))
                                all.try_emplace(v.name(), std::move(v));
                        }
    // The second depth layer's impostor programs for every shape and depth encoding.
    for (DepthMode depth : {DepthMode::Standard, DepthMode::Log, DepthMode::Reversed})
        for (ParticleShape shape : {ParticleShape::Sphere, ParticleShape::Ellipsoid})
            for (PerSetDevice where : {PerSetDevice::Cpu, PerSetDevice::Gpu}) {
                Settings a;
                a.ao.method = AoMethod::Gtao;
                a.ao.layers = 2;
                a.depth = depth;
                a.particles.shape = shape;
                a.particles.bodySpherePixels = 4096.0;
                a.perSet = where;
                for (ProgramVariant& v : programVariants(a, false))
                    all.try_emplace(v.name(), std::move(v));
            }
    // The emissive light's, with and without occlusion and shadows (it lights only where
    // something emits).
    for (EmissiveMethod method :
         {EmissiveMethod::PointLights, EmissiveMethod::Ssem, EmissiveMethod::SsemTarget})
        for (EmissiveBlur blur : {EmissiveBlur::None, EmissiveBlur::DepthAware})
            for (AoMethod ao : {AoMethod::None, AoMethod::Gtao})
                for (ShadowMode shadows : {ShadowMode::None, ShadowMode::Map}) {
                    Settings a;
                    a.emissive.method = method;
                    a.emissive.blur = blur;
                    a.ao.method = ao;
                    a.shadows = shadows;
                    for (ProgramVariant& v : programVariants(a, true, true))
                        all.try_emplace(v.name(), std::move(v));
                }
    // The sub-pixel emitters' halo (particles.halo_pixels).
    {
        Settings a;
        a.particles.haloPixels = 1.0;
        for (ProgramVariant& v : programVariants(a, true)) all.try_emplace(v.name(), std::move(v));
    }
    // The atmosphere's, one per end point.
    for (AtmosphereEndPoint endPoint : {AtmosphereEndPoint::Impostor, AtmosphereEndPoint::Filtered,
                                        AtmosphereEndPoint::Sphere, AtmosphereEndPoint::Blend}) {
        Settings a;
        a.atmosphere.endPoint = endPoint;
        for (ProgramVariant& v : programVariants(a, false, false, true))
            all.try_emplace(v.name(), std::move(v));
    }
    // The whole-body sphere's, in every depth encoding, with the shadow map and the emitter
    // target; on the GPU path with the masked particles' (droplets' ellipsoids among them), the
    // masked halo's and gradient gather's, and REPLACED.
    for (DepthMode depth : {DepthMode::Standard, DepthMode::Log, DepthMode::Reversed})
        for (PerSetDevice where : {PerSetDevice::Cpu, PerSetDevice::Gpu}) {
            Settings a;
            a.depth = depth;
            a.perSet = where;
            a.particles.bodySpherePixels = 1.0;
            a.particles.haloPixels = 1.0;
            a.emissive.method = EmissiveMethod::SsemTarget;
            for (ProgramVariant& v : programVariants(a, true, true))
                all.try_emplace(v.name(), std::move(v));
        }
    // The error split's (error_split.h): the reference's depth, and shade with its light.
    for (DepthMode depth : {DepthMode::Standard, DepthMode::Log, DepthMode::Reversed}) {
        ProgramVariant v =
            ProgramVariant::draw("fullscreen.vert", "exact_depth.frag", {depthDefine(depth)});
        all.try_emplace(v.name(), std::move(v));
    }
    for (bool emits : {false, true})
        for (bool occlusion : {false, true})
            for (bool emissiveLight : {false, true}) {
                if (emissiveLight && !emits) continue;
                std::vector<std::string> defines =
                    shadeDefines(ShadowMode::None, {}, emits, occlusion, emissiveLight);
                defines.front() = "VISIBILITY_TEXTURE";
                ProgramVariant v = ProgramVariant::draw("fullscreen.vert", "shade.frag", defines);
                all.try_emplace(v.name(), std::move(v));
            }
    std::vector<ProgramVariant> out;
    for (auto& [name, v] : all) out.push_back(std::move(v));
    return out;
}

std::vector<CompileFailure> compileEach(ProgramCache& programs,
                                        std::span<const ProgramVariant> variants,
                                        const IncludedFile* user) {
    std::vector<CompileFailure> failures;
    for (const ProgramVariant& v : variants) {
        try {
            const gl::Program& program = v.build(programs, user);
            if (v.compute.starts_with("per_set_")) checkPerSetLayouts(program);
        } catch (const gl::Error& e) {
            failures.push_back({v.name(), e.what()});
        }
    }
    return failures;
}

}  // namespace twinrender::realtime
