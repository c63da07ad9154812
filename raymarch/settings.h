// The raymarcher's settings: the [raymarch] section of a scene, or --set raymarch.KEY=VALUE.
#pragma once

#include <nlohmann/json.hpp>

#include "core/parameters.h"

namespace twinrender::raymarch {

struct Settings {
    double surfaceLevel = 0.13;   // level of the colour field, (0, 10]; OpenSPH's default
    bool shadows = true;          // trace shadow rays
    bool spheres = false;         // plain spheres instead of the implicit surface (cost floor)
    double sphereRadius = 0.5;    // spheres mode: sphere radius in units of h, (0, 2]
    int spp = 1;                  // samples per pixel, 1..16384; 1 = the pixel centre
    double rootTolerance = 1e-4;  // root accuracy along the ray, in units of h, [1e-8, 0.1]
    double segmentLength = 2.0;   // candidates are gathered per segment of this many h, [0.5, 64]
    double stepWindow = 0.5;      // window of the curvature bound, in units of h, [0.01, 4]
    int maxIterations = 256;      // field evaluations per segment before a ray is unresolved
    int tileSize = 16;            // pixels per tile side, 4..256
    // Sun directions per shadow sample when light.angular_radius > 0, 1..1024
    // (raymarch/sun_disc.h); the visibility is then a multiple of 1 / sun_samples.
    int sunSamples = 64;
    // Cosine-weighted directions traced per hit sample for the ambient occlusion when
    // light.ao_radius > 0, a square number 1..4096 (a side x side stratified pattern,
    // raymarch/ao_hemisphere.h). The per-pixel standard error is at most 0.5 / sqrt(ao_samples)
    // (the frame's ao_standard_error counter states the mean).
    int aoSamples = 64;
    // Directions traced per hit sample toward each emitting body when light.emissive_light is
    // on, a square number 1..4096 (a side x side stratified pattern over the cone the body's
    // bounding sphere subtends, raymarch/emitter_cone.h); the frame's
    // irradiance_standard_error counter states the resulting noise.
    int emissiveSamples = 64;
    // Per-pixel standard-error targets of the three secondary estimates (raymarch/
    // progressive_strata.h): with a target > 0 each hit sample takes its rays in stratified
    // rounds to 1, 4, 16, 64, ... until the estimate's standard error is below it (tested from
    // 16 rays on) or the cap, the largest power of 4 not above 4 x the matching *_samples
    // (256 for 64), is reached. 0: the fixed count of *_samples for every pixel.
    double aoError = 0.0;        // of the open fraction, [0, 0.5]
    double emissiveError = 0.0;  // of the irradiance's luminance, [0, 1e6]
    double sunError = 0.0;       // of the sun's visible share, [0, 0.5]
};

// Reads every key of the table and rejects the ones it does not know.
Settings parseSettings(const core::ParameterTable& table);
// The side of the ambient occlusion's pattern: sqrt(ao_samples).
int aoSide(const Settings& settings);
// The side of the emitters' pattern: sqrt(emissive_samples).
int emissiveSide(const Settings& settings);
// Every setting by its scene key, for the frame's JSON.
nlohmann::json toJson(const Settings& settings);

}  // namespace twinrender::raymarch
