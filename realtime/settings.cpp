#include "realtime/settings.h"

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
    return ShadowMode::Map;
}

}  // namespace

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
    }
    return "map";
}

std::string_view toString(NormalModel model) {
    switch (model) {
        case NormalModel::Blend:
            return "blend";
        case NormalModel::Gradient:
            return "gradient";
        case NormalModel::Field:
            break;
    }
    return "field";
}

std::string_view toString(RadiusModel model) {
    return model == RadiusModel::Fixed ? "fixed" : "field";
}

Settings parseSettings(const core::ParameterTable& t) {
    const Settings d;  // defaults
    Settings s;
    s.depth = parseDepthMode(
        t.getEnum("depth", std::string(toString(d.depth)), {"log", "standard", "reversed"}));
    s.shadows = parseShadowMode(
        t.getEnum("shadows", std::string(toString(d.shadows)), {"map", "pcf", "spheres", "none"}));
    s.particles.radiusScale =
        t.getDouble("particles.radius_scale", d.particles.radiusScale, 1e-6, 10.0);
    s.particles.radius = t.getEnum("particles.radius", std::string(toString(d.particles.radius)),
                                   {"field", "fixed"}) == "fixed"
                             ? RadiusModel::Fixed
                             : RadiusModel::Field;
    s.particles.crossingScale =
        t.getDouble("particles.crossing_scale", d.particles.crossingScale, 1.0, 4.0);
    s.particles.surfaceLevel =
        t.getDouble("particles.surface_level", d.particles.surfaceLevel, 1e-6, 1e6);
    const std::string normal =
        t.getEnum("particles.normal", std::string(toString(d.particles.normal)),
                  {"field", "blend", "gradient"});
    s.particles.normal = normal == "blend"      ? NormalModel::Blend
                         : normal == "gradient" ? NormalModel::Gradient
                                                : NormalModel::Field;
    s.particles.sphereNormalWeight =
        t.getDouble("particles.sphere_normal_weight", d.particles.sphereNormalWeight, 0.0, 1.0);
    s.particles.cullHidden = t.getBool("particles.cull_hidden", d.particles.cullHidden);

    s.shadowMap.resolution =
        static_cast<int>(t.getInt("shadow_map.resolution", d.shadowMap.resolution, 16, 16384));
    s.shadowMap.bias = t.getDouble("shadow_map.bias", d.shadowMap.bias, 0.0, 10.0);
    s.shadowMap.slopeBias = t.getDouble("shadow_map.slope_bias", d.shadowMap.slopeBias, 0.0, 100.0);
    s.shadowMap.pcfRadius = t.getDouble("shadow_map.pcf_radius", d.shadowMap.pcfRadius, 0.0, 16.0);

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
        {"realtime.shadows", toString(s.shadows)},
        {"realtime.particles.radius_scale", s.particles.radiusScale},
        {"realtime.particles.radius", toString(s.particles.radius)},
        {"realtime.particles.surface_level", s.particles.surfaceLevel},
        {"realtime.particles.crossing_scale", s.particles.crossingScale},
        {"realtime.particles.normal", toString(s.particles.normal)},
        {"realtime.particles.sphere_normal_weight", s.particles.sphereNormalWeight},
        {"realtime.particles.cull_hidden", s.particles.cullHidden},
        {"realtime.shadow_map.resolution", s.shadowMap.resolution},
        {"realtime.shadow_map.bias", s.shadowMap.bias},
        {"realtime.shadow_map.slope_bias", s.shadowMap.slopeBias},
        {"realtime.shadow_map.pcf_radius", s.shadowMap.pcfRadius},
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
