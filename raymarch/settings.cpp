#include "raymarch/settings.h"

#include <fmt/format.h>

#include <cmath>

#include "core/error.h"

namespace twinrender::raymarch {

Settings parseSettings(const core::ParameterTable& t) {
    Settings s;
    s.surfaceLevel = t.getDouble("surface_level", s.surfaceLevel, 1e-6, 10.0);
    s.shadows = t.getBool("shadows", s.shadows);
    s.spheres = t.getBool("spheres", s.spheres);
    s.sphereRadius = t.getDouble("sphere_radius", s.sphereRadius, 1e-3, 2.0);
    s.spp = static_cast<int>(t.getInt("spp", s.spp, 1, 16384));
    s.rootTolerance = t.getDouble("root_tolerance", s.rootTolerance, 1e-8, 0.1);
    s.segmentLength = t.getDouble("segment_length", s.segmentLength, 0.5, 64.0);
    s.stepWindow = t.getDouble("step_window", s.stepWindow, 0.01, 4.0);
    s.maxIterations = static_cast<int>(t.getInt("max_iterations", s.maxIterations, 8, 100000));
    s.tileSize = static_cast<int>(t.getInt("tile_size", s.tileSize, 4, 256));
    s.sunSamples = static_cast<int>(t.getInt("sun_samples", s.sunSamples, 1, 1024));
    s.aoSamples = static_cast<int>(t.getInt("ao_samples", s.aoSamples, 1, 4096));
    s.emissiveSamples = static_cast<int>(t.getInt("emissive_samples", s.emissiveSamples, 1, 4096));
    s.aoError = t.getDouble("ao_error", s.aoError, 0.0, 0.5);
    s.emissiveError = t.getDouble("emissive_error", s.emissiveError, 0.0, 1e6);
    s.sunError = t.getDouble("sun_error", s.sunError, 0.0, 0.5);
    for (const auto& [key, value] : {std::pair<const char*, int>{"ao_samples", s.aoSamples},
                                     {"emissive_samples", s.emissiveSamples}}) {
        const int side = static_cast<int>(std::lround(std::sqrt(double(value))));
        if (side * side != value)
            throw core::InputError(
                fmt::format("{} = {} is not a square number: the directions are a side x side "
                            "pattern; use one of 16, 36, 64, 100, 256, 1024",
                            t.describe(key), value));
    }
    t.checkAllRead();
    return s;
}

int aoSide(const Settings& settings) {
    return static_cast<int>(std::lround(std::sqrt(double(settings.aoSamples))));
}

int emissiveSide(const Settings& settings) {
    return static_cast<int>(std::lround(std::sqrt(double(settings.emissiveSamples))));
}

nlohmann::json toJson(const Settings& s) {
    return {{"raymarch.surface_level", s.surfaceLevel},
            {"raymarch.shadows", s.shadows},
            {"raymarch.spheres", s.spheres},
            {"raymarch.sphere_radius", s.sphereRadius},
            {"raymarch.spp", s.spp},
            {"raymarch.root_tolerance", s.rootTolerance},
            {"raymarch.segment_length", s.segmentLength},
            {"raymarch.step_window", s.stepWindow},
            {"raymarch.max_iterations", s.maxIterations},
            {"raymarch.tile_size", s.tileSize},
            {"raymarch.sun_samples", s.sunSamples},
            {"raymarch.ao_samples", s.aoSamples},
            {"raymarch.emissive_samples", s.emissiveSamples},
            {"raymarch.ao_error", s.aoError},
            {"raymarch.emissive_error", s.emissiveError},
            {"raymarch.sun_error", s.sunError}};
}

}  // namespace twinrender::raymarch
