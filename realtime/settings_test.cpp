#include "realtime/settings.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace twinrender::realtime {
namespace {

core::ParameterTable table(
    std::initializer_list<std::pair<std::string, core::ParameterTable::Value>> entries) {
    core::ParameterTable t("realtime", "scene.toml");
    int line = 1;
    for (const auto& [key, value] : entries)
        t.set(key, value, "scene.toml:" + std::to_string(line++) + ":1");
    return t;
}

TEST(Settings, DefaultsFollowScenesMd) {
    const Settings s = parseSettings(table({}));
    EXPECT_EQ(s.depth, DepthMode::Log);
    EXPECT_EQ(s.shadows, ShadowMode::Map);
    EXPECT_EQ(s.shadowMap.resolution, 2048);
    EXPECT_TRUE(s.ssss.enabled);
    EXPECT_TRUE(s.ssss.separable);
    EXPECT_TRUE(s.particles.cullHidden);
    EXPECT_EQ(s.particles.minPixels, 0.0);         // off: every impostor at its own size
    EXPECT_EQ(s.particles.bodySpherePixels, 0.0);  // off: every body drawn as its particles
}

TEST(Settings, ReadsEveryKey) {
    const Settings s = parseSettings(table({{"depth", std::string("reversed")},
                                            {"gbuffer.format", std::string("compact")},
                                            {"per_set", std::string("cpu")},
                                            {"per_set_fallback", false},
                                            {"shadows", std::string("pcf")},
                                            {"particles.radius_scale", 1.1},
                                            {"particles.cull_hidden", false},
                                            {"particles.normal", std::string("blend")},
                                            {"particles.sphere_normal_weight", 0.5},
                                            {"particles.droplet_atoms", std::int64_t(5)},
                                            {"particles.interior_level", 0.9},
                                            {"particles.min_pixels", 1.5},
                                            {"particles.body_sphere_pixels", 8.0},
                                            {"shadow_map.resolution", std::int64_t(512)},
                                            {"shadow_map.bias", 0.25},
                                            {"shadow_map.slope_bias", 3.0},
                                            {"shadow_map.pcf_radius", std::int64_t(2)},
                                            {"ssss.enabled", false},
                                            {"ssss.radius_scale", 1.5},
                                            {"ssss.depth_limit", 4.0},
                                            {"ssss.iterations", std::int64_t(3)},
                                            {"ssss.separable", false},
                                            {"ssss.max_taps", std::int64_t(12)},
                                            {"bloom.enabled", false},
                                            {"bloom.strength", 0.2},
                                            {"bloom.threshold", 2.0}}));
    EXPECT_EQ(s.depth, DepthMode::Reversed);
    EXPECT_EQ(s.gbufferFormat, GBufferFormat::Compact);
    EXPECT_EQ(s.perSet, PerSetDevice::Cpu);
    EXPECT_FALSE(s.perSetFallback);
    EXPECT_EQ(s.shadows, ShadowMode::Pcf);
    EXPECT_DOUBLE_EQ(s.particles.radiusScale, 1.1);
    EXPECT_FALSE(s.particles.cullHidden);
    EXPECT_EQ(s.particles.normal, NormalModel::Blend);
    EXPECT_DOUBLE_EQ(s.particles.sphereNormalWeight, 0.5);
    EXPECT_EQ(s.particles.dropletAtoms, 5);
    EXPECT_DOUBLE_EQ(s.particles.interiorLevel, 0.9);
    EXPECT_DOUBLE_EQ(s.particles.minPixels, 1.5);
    EXPECT_DOUBLE_EQ(s.particles.bodySpherePixels, 8.0);
    EXPECT_EQ(s.shadowMap.resolution, 512);
    EXPECT_DOUBLE_EQ(s.shadowMap.bias, 0.25);
    EXPECT_DOUBLE_EQ(s.shadowMap.slopeBias, 3.0);
    EXPECT_DOUBLE_EQ(s.shadowMap.pcfRadius, 2.0);
    EXPECT_FALSE(s.ssss.enabled);
    EXPECT_DOUBLE_EQ(s.ssss.radiusScale, 1.5);
    EXPECT_DOUBLE_EQ(s.ssss.depthLimit, 4.0);
    EXPECT_EQ(s.ssss.iterations, 3);
    EXPECT_FALSE(s.ssss.separable);
    EXPECT_EQ(s.ssss.maxTaps, 12);
    EXPECT_FALSE(s.bloom.enabled);
    EXPECT_DOUBLE_EQ(s.bloom.strength, 0.2);
    EXPECT_DOUBLE_EQ(s.bloom.threshold, 2.0);
    // Every setting appears in the JSON under its dotted key.
    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j.at("realtime.depth"), "reversed");
    EXPECT_EQ(j.at("realtime.ssss.iterations"), 3);
    EXPECT_EQ(j.at("realtime.particles.normal"), "blend");
    EXPECT_EQ(j.at("realtime.per_set"), "cpu");
    EXPECT_EQ(j.at("realtime.per_set_fallback"), false);
    EXPECT_EQ(j.at("realtime.particles.droplet_atoms"), 5);
    EXPECT_EQ(j.at("realtime.particles.interior_level"), 0.9);
    EXPECT_EQ(j.at("realtime.gbuffer.format"), "compact");
    EXPECT_EQ(j.at("realtime.particles.min_pixels"), 1.5);
    EXPECT_EQ(j.at("realtime.particles.body_sphere_pixels"), 8.0);
    EXPECT_EQ(j.at("realtime.ao.depth"), "filtered");
    EXPECT_EQ(j.at("realtime.ao.thickness"), 0.0);
    EXPECT_EQ(j.at("realtime.ao.layers"), 1);
    EXPECT_EQ(j.at("realtime.ao.gtao_angle_bias"), 10.0);
    EXPECT_EQ(j.size(), 85u);
}

TEST(Settings, ReadsTheAtmosphereKeys) {
    const Settings d = parseSettings(table({}));
    EXPECT_EQ(d.atmosphere.endPoint, AtmosphereEndPoint::Filtered);
    EXPECT_EQ(d.atmosphere.steps, 0);
    const Settings s = parseSettings(table({{"atmosphere.end_point", std::string("blend")},
                                            {"atmosphere.blend_near", 1.5},
                                            {"atmosphere.blend_far", 6.0},
                                            {"atmosphere.steps", std::int64_t(12)}}));
    EXPECT_EQ(s.atmosphere.endPoint, AtmosphereEndPoint::Blend);
    EXPECT_DOUBLE_EQ(s.atmosphere.blendNear, 1.5);
    EXPECT_DOUBLE_EQ(s.atmosphere.blendFar, 6.0);
    EXPECT_EQ(s.atmosphere.steps, 12);
    EXPECT_EQ(toJson(s).at("realtime.atmosphere.end_point"), "blend");
    EXPECT_THROW(parseSettings(table({{"atmosphere.blend_near", 5.0}})), core::InputError);
    EXPECT_THROW(parseSettings(table({{"atmosphere.end_point", std::string("depth")}})),
                 core::InputError);
}

// The spheres replace particles in the CPU's packing, and through a mask of the replaced
// bodies on the GPU path (per_set.cpp): either per_set takes the key.
TEST(Settings, TheWholeBodySphereWorksWithEitherPerSetDevice) {
    for (const char* where : {"gpu", "cpu"}) {
        const Settings s = parseSettings(
            table({{"particles.body_sphere_pixels", 4.0}, {"per_set", std::string(where)}}));
        EXPECT_EQ(s.particles.bodySpherePixels, 4.0) << where;
        EXPECT_EQ(toString(s.perSet), where);
    }
    EXPECT_THROW(parseSettings(table({{"particles.body_sphere_pixels", -1.0}})),
                 twinrender::core::InputError);
}

TEST(Settings, ReadsTheAmbientOcclusionKeys) {
    const Settings d = parseSettings(table({}));
    EXPECT_EQ(d.ao.method, AoMethod::Traced);
    // Asked for by default; a frame runs it where the scene's light.ao_radius is above 0.
    EXPECT_TRUE(usesAmbientOcclusion(d));
    EXPECT_FALSE(usesAmbientOcclusion(parseSettings(table({{"ao.method", std::string("none")}}))));
    const Settings s = parseSettings(table({{"ao.method", std::string("gtao")},
                                            {"ao.slices", std::int64_t(6)},
                                            {"ao.steps", std::int64_t(12)},
                                            {"ao.blur", std::string("flat")},
                                            {"ao.blur_radius", std::int64_t(3)},
                                            {"ao.noise", std::string("blue")},
                                            {"ao.max_pixels", 100.0}}));
    EXPECT_EQ(s.ao.method, AoMethod::Gtao);
    EXPECT_TRUE(usesAmbientOcclusion(s));
    EXPECT_EQ(s.ao.slices, 6);
    EXPECT_EQ(s.ao.steps, 12);
    EXPECT_EQ(s.ao.blur, AoBlur::Flat);
    EXPECT_EQ(s.ao.blurRadius, 3);
    EXPECT_EQ(s.ao.noise, AoNoise::Blue);
    EXPECT_DOUBLE_EQ(s.ao.maxPixels, 100.0);
    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j.at("realtime.ao.method"), "gtao");
    EXPECT_EQ(j.at("realtime.ao.noise"), "blue");
    EXPECT_EQ(j.at("realtime.ao.blur"), "flat");
    EXPECT_THROW(parseSettings(table({{"ao.method", std::string("hbao+")}})),
                 twinrender::core::InputError);
}

TEST(Settings, ReadsTheTracedOcclusionKeys) {
    EXPECT_EQ(parseSettings(table({})).ao.rays, 16);
    const Settings s =
        parseSettings(table({{"ao.method", std::string("traced")}, {"ao.rays", std::int64_t(64)}}));
    EXPECT_EQ(s.ao.method, AoMethod::Traced);
    EXPECT_TRUE(usesAmbientOcclusion(s));
    EXPECT_EQ(s.ao.rays, 64);
    EXPECT_EQ(toJson(s).at("realtime.ao.method"), "traced");
    EXPECT_EQ(toJson(s).at("realtime.ao.rays"), 64);
    // Outside [1, 256] is bad input, named by its key.
    for (const std::int64_t rays : {std::int64_t(0), std::int64_t(257)}) {
        try {
            parseSettings(table({{"ao.rays", rays}}));
            ADD_FAILURE() << rays;
        } catch (const twinrender::core::InputError& e) {
            EXPECT_NE(std::string(e.what()).find("ao.rays"), std::string::npos) << e.what();
        }
    }
}

TEST(Settings, ReadsTheEmissiveKeys) {
    const Settings d = parseSettings(table({}));
    EXPECT_EQ(d.emissive.method, EmissiveMethod::PointLights);
    EXPECT_EQ(d.emissive.blur, EmissiveBlur::DepthAware);
    // Only the scene's light.emissive_light with something emitting runs the pass.
    EXPECT_FALSE(usesEmissiveLight(d, false, true));
    EXPECT_FALSE(usesEmissiveLight(d, true, false));
    EXPECT_TRUE(usesEmissiveLight(d, true, true));
    const Settings s = parseSettings(table({{"emissive.method", std::string("ssem")},
                                            {"emissive.directions", std::int64_t(32)},
                                            {"emissive.steps", std::int64_t(12)},
                                            {"emissive.max_pixels", 100.0},
                                            {"emissive.thickness", 2.5},
                                            {"emissive.blur", std::string("none")},
                                            {"emissive.blur_radius", std::int64_t(3)}}));
    EXPECT_EQ(s.emissive.method, EmissiveMethod::Ssem);
    EXPECT_EQ(s.emissive.directions, 32);
    EXPECT_EQ(s.emissive.steps, 12);
    EXPECT_DOUBLE_EQ(s.emissive.maxPixels, 100.0);
    EXPECT_DOUBLE_EQ(s.emissive.thickness, 2.5);
    EXPECT_EQ(s.emissive.blur, EmissiveBlur::None);
    EXPECT_EQ(s.emissive.blurRadius, 3);
    EXPECT_FALSE(s.emissive == d.emissive);
    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j.at("realtime.emissive.method"), "ssem");
    EXPECT_EQ(j.at("realtime.emissive.directions"), 32);
    EXPECT_EQ(j.at("realtime.emissive.blur"), "none");
    EXPECT_EQ(j.at("realtime.emissive.thickness"), 2.5);
    // "ssem_target": the emitter target's field of view and aspect.
    EXPECT_DOUBLE_EQ(d.emissive.targetFovScale, 2.0);
    EXPECT_TRUE(d.emissive.targetAspect);
    const Settings target = parseSettings(table({{"emissive.method", std::string("ssem_target")},
                                                 {"emissive.target_fov_scale", 3.0},
                                                 {"emissive.target_aspect", false}}));
    EXPECT_EQ(target.emissive.method, EmissiveMethod::SsemTarget);
    EXPECT_DOUBLE_EQ(target.emissive.targetFovScale, 3.0);
    EXPECT_FALSE(target.emissive.targetAspect);
    EXPECT_EQ(toJson(target).at("realtime.emissive.method"), "ssem_target");
    EXPECT_EQ(toJson(target).at("realtime.emissive.target_aspect"), false);
    const Settings none = parseSettings(table({{"emissive.method", std::string("none")}}));
    EXPECT_FALSE(usesEmissiveLight(none, true, true));
    const std::vector<std::pair<std::string, core::ParameterTable::Value>> bad = {
        {"emissive.method", std::string("ssgi")}, {"emissive.directions", std::int64_t(0)},
        {"emissive.steps", std::int64_t(65)},     {"emissive.thickness", 0.0},
        {"emissive.blur", std::string("flat")},   {"emissive.target_fov_scale", 0.5}};
    for (const auto& [key, value] : bad) {
        try {
            parseSettings(table({{key, value}}));
            ADD_FAILURE() << key << " accepted";
        } catch (const core::InputError& e) {
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    }
}

TEST(Settings, ReadsTheParticleShapeKeys) {
    const Settings d = parseSettings(table({}));
    EXPECT_EQ(d.particles.shape, ParticleShape::Sphere);
    EXPECT_DOUBLE_EQ(d.particles.anisotropy.smoothing, 0.9);
    EXPECT_DOUBLE_EQ(d.particles.anisotropy.maxAxisRatio, 4.0);
    EXPECT_EQ(d.particles.anisotropy.minNeighbours, 25);
    EXPECT_EQ(d.particles.anisotropy.anchor, EllipsoidAnchor::Surface);
    const Settings s =
        parseSettings(table({{"particles.shape", std::string("ellipsoid")},
                             {"particles.normal", std::string("sphere")},
                             {"particles.anisotropy.smoothing", 0.5},
                             {"particles.anisotropy.max_axis_ratio", 3.0},
                             {"particles.anisotropy.min_neighbours", 10L},
                             {"particles.anisotropy.anchor", std::string("centre")}}));
    EXPECT_EQ(s.particles.shape, ParticleShape::Ellipsoid);
    EXPECT_EQ(s.particles.normal, NormalModel::Sphere);
    EXPECT_DOUBLE_EQ(s.particles.anisotropy.smoothing, 0.5);
    EXPECT_DOUBLE_EQ(s.particles.anisotropy.maxAxisRatio, 3.0);
    EXPECT_EQ(s.particles.anisotropy.minNeighbours, 10);
    EXPECT_EQ(s.particles.anisotropy.anchor, EllipsoidAnchor::Centre);
    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j.at("realtime.particles.shape"), "ellipsoid");
    EXPECT_EQ(j.at("realtime.particles.normal"), "sphere");
    EXPECT_EQ(j.at("realtime.particles.anisotropy.smoothing"), 0.5);
    EXPECT_EQ(j.at("realtime.particles.anisotropy.max_axis_ratio"), 3.0);
    EXPECT_EQ(j.at("realtime.particles.anisotropy.min_neighbours"), 10);
    EXPECT_EQ(j.at("realtime.particles.anisotropy.anchor"), "centre");
}

TEST(Settings, ReadsTheShadowFilterKeys) {
    const Settings d = parseSettings(table({}));
    EXPECT_DOUBLE_EQ(d.shadowMap.blurRadius, 2.0);
    EXPECT_DOUBLE_EQ(d.shadowMap.esmExponent, 80.0);
    EXPECT_EQ(d.shadowMap.esmForm, EsmForm::Warp);
    const Settings s = parseSettings(table({{"shadows", std::string("evsm")},
                                            {"shadow_map.blur_radius", 3.5},
                                            {"shadow_map.esm_exponent", 20.0},
                                            {"shadow_map.esm_form", std::string("seed")},
                                            {"shadow_map.vsm_bleed_reduction", 0.4},
                                            {"shadow_map.evsm_positive_exponent", 30.0},
                                            {"shadow_map.evsm_negative_exponent", 10.0}}));
    EXPECT_EQ(s.shadows, ShadowMode::Evsm);
    EXPECT_TRUE(usesShadowMap(s.shadows) && usesFilteredShadowMap(s.shadows));
    EXPECT_FALSE(usesFilteredShadowMap(ShadowMode::Pcf));
    EXPECT_DOUBLE_EQ(s.shadowMap.blurRadius, 3.5);
    EXPECT_DOUBLE_EQ(s.shadowMap.esmExponent, 20.0);
    EXPECT_EQ(s.shadowMap.esmForm, EsmForm::Seed);
    EXPECT_DOUBLE_EQ(s.shadowMap.vsmBleedReduction, 0.4);
    EXPECT_DOUBLE_EQ(s.shadowMap.evsmPositiveExponent, 30.0);
    EXPECT_DOUBLE_EQ(s.shadowMap.evsmNegativeExponent, 10.0);
    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j.at("realtime.shadows"), "evsm");
    EXPECT_EQ(j.at("realtime.shadow_map.esm_form"), "seed");
    EXPECT_EQ(j.at("realtime.shadow_map.blur_radius"), 3.5);
}

void expectError(const core::ParameterTable& t, const std::string& fragment) {
    try {
        parseSettings(t);
        FAIL() << "no error";
    } catch (const core::InputError& e) {
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
}

TEST(Settings, UnknownKeyNamesFileLineAndKey) {
    expectError(table({{"ssss.enabeld", true}}), "scene.toml:1:1");
    expectError(table({{"ssss.enabeld", true}}), "realtime.ssss.enabeld");
}

TEST(Settings, RejectsBadValues) {
    expectError(table({{"depth", std::string("logarithmic")}}), "realtime.depth");
    expectError(table({{"shadows", std::string("pcss")}}), "realtime.shadows");
    expectError(table({{"shadow_map.esm_form", std::string("log")}}),
                "realtime.shadow_map.esm_form");
    // The exponential warps must fit a 32-bit float (settings.h).
    expectError(table({{"shadow_map.esm_exponent", 90.0}}), "out of range");
    expectError(table({{"shadow_map.evsm_positive_exponent", 45.0}}), "out of range");
    expectError(table({{"shadow_map.vsm_bleed_reduction", 1.0}}), "out of range");
    expectError(table({{"shadow_map.blur_radius", -1.0}}), "out of range");
    expectError(table({{"particles.normal", std::string("flat")}}), "realtime.particles.normal");
    expectError(table({{"particles.shape", std::string("disc")}}), "realtime.particles.shape");
    expectError(table({{"particles.anisotropy.smoothing", 1.5}}), "out of range");
    expectError(table({{"particles.anisotropy.max_axis_ratio", 0.5}}), "out of range");
    expectError(table({{"particles.anisotropy.min_neighbours", 0L}}), "out of range");
    expectError(table({{"particles.anisotropy.anchor", std::string("top")}}),
                "realtime.particles.anisotropy.anchor");
    expectError(table({{"shadow_map.resolution", std::int64_t(1 << 20)}}), "out of range");
    expectError(table({{"ssss.iterations", std::int64_t(0)}}), "out of range");
    expectError(table({{"ssss.enabled", std::int64_t(1)}}), "wrong type");
}

TEST(Settings, ReadsTheSurfaceMethodAndEachFiltersKeys) {
    const Settings s = parseSettings(table({{"surface.method", std::string("narrow_range")},
                                            {"surface.bilateral.radius", 2.0},
                                            {"surface.bilateral.depth_sigma", 5.0},
                                            {"surface.bilateral.iterations", std::int64_t(2)},
                                            {"surface.bilateral.separable", true},
                                            {"surface.bilateral.max_radius_px", 9.0},
                                            {"surface.narrow_range.radius", 1.5},
                                            {"surface.narrow_range.threshold", 8.0},
                                            {"surface.narrow_range.clamp", 2.0},
                                            {"surface.narrow_range.iterations", std::int64_t(4)},
                                            {"surface.narrow_range.separable", false},
                                            {"surface.narrow_range.max_radius_px", 50.0},
                                            {"surface.curvature_flow.iterations", std::int64_t(60)},
                                            {"surface.curvature_flow.time_step", 0.1},
                                            {"surface.curvature_flow.depth_limit", 3.0}}));
    EXPECT_EQ(s.surface.method, SurfaceMethod::NarrowRange);
    EXPECT_DOUBLE_EQ(s.surface.bilateral.radius, 2.0);
    EXPECT_DOUBLE_EQ(s.surface.bilateral.depthSigma, 5.0);
    EXPECT_EQ(s.surface.bilateral.iterations, 2);
    EXPECT_TRUE(s.surface.bilateral.separable);
    EXPECT_DOUBLE_EQ(s.surface.bilateral.maxRadiusPx, 9.0);
    EXPECT_DOUBLE_EQ(s.surface.narrowRange.radius, 1.5);
    EXPECT_DOUBLE_EQ(s.surface.narrowRange.threshold, 8.0);
    EXPECT_DOUBLE_EQ(s.surface.narrowRange.clamp, 2.0);
    EXPECT_EQ(s.surface.narrowRange.iterations, 4);
    EXPECT_FALSE(s.surface.narrowRange.separable);
    EXPECT_DOUBLE_EQ(s.surface.narrowRange.maxRadiusPx, 50.0);
    EXPECT_EQ(s.surface.curvatureFlow.iterations, 60);
    EXPECT_DOUBLE_EQ(s.surface.curvatureFlow.timeStep, 0.1);
    EXPECT_DOUBLE_EQ(s.surface.curvatureFlow.depthLimit, 3.0);
    EXPECT_TRUE(usesSurfaceFilter(s));
    EXPECT_FALSE(usesSsss(s));
    EXPECT_EQ(toJson(s).at("realtime.surface.method"), "narrow_range");
}

// ssss.enabled = false keeps meaning no smoothing; the default method is SSSS.
TEST(Settings, SsssEnabledFalseMeansNoSmoothing) {
    EXPECT_TRUE(usesSsss(parseSettings(table({}))));
    const Settings off = parseSettings(table({{"ssss.enabled", false}}));
    EXPECT_FALSE(usesSsss(off));
    EXPECT_FALSE(usesSurfaceFilter(off));
}

TEST(Settings, UserShaderIsReadRelativeToTheSceneFile) {
    const auto dir = std::filesystem::temp_directory_path() / "twinrender_settings_shader";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "mine.glsl") << "void filterSurface(ivec2 p, inout SurfaceSample s) {}\n";
    core::ParameterTable t("realtime", (dir / "scene.toml").string());
    t.set("surface.shader", std::string("mine.glsl"), "scene.toml:3:1");
    const Settings s = parseSettings(t);
    EXPECT_EQ(s.surface.method, SurfaceMethod::Shader);
    EXPECT_EQ(s.surface.shaderPath, (dir / "mine.glsl").string());
    EXPECT_NE(s.surface.shaderSource.find("filterSurface"), std::string::npos);
    std::filesystem::remove_all(dir);
}

TEST(Settings, UserShaderErrorsNameTheKeys) {
    expectError(table({{"surface.method", std::string("shader")}}),
                "realtime.surface.shader = PATH");
    expectError(table({{"surface.shader", std::string("x.glsl")},
                       {"surface.method", std::string("bilateral")}}),
                "surface.method = \"shader\"");
    expectError(table({{"surface.shader", std::string("/nonexistent/x.glsl")}}),
                "cannot read the shader file '/nonexistent/x.glsl'");
    expectError(table({{"surface.method", std::string("blur")}}), "realtime.surface.method");
    expectError(table({{"surface.curvature_flow.time_step", 0.5}}), "out of range");
}

}  // namespace
}  // namespace twinrender::realtime
