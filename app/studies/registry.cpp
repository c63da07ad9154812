// The list of studies: each study's name, title, question, scene, axes and columns, with the
// points and the conclusion of its file (app/studies/<name>.cpp). The CLI's help and its name
// checks are built from it.
#include <fmt/format.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "app/studies.h"
#include "app/studies/study_list.h"
#include "compare/metric_table.h"

namespace twinrender::app {

namespace {

// Every metric a study charts or tabulates must be one of compare's metric table: a typo would
// show as an empty column.
std::vector<StudyDef> checked(std::vector<StudyDef> defs) {
    for (const StudyDef& d : defs) {
        std::vector<std::string> keys = d.columns;
        keys.push_back(d.metric);
        for (const std::string& k : keys)
            if (!compare::findMetric(k))
                throw std::logic_error(
                    fmt::format("study {}: '{}' is not in compare's metric table", d.name, k));
    }
    return defs;
}

}  // namespace

const std::vector<StudyDef>& studies() {
    // What the studies of the screen-space smoothing tabulate.
    const std::vector<std::string> smoothingColumns = {"normal.mean_deg", "normal.p95_deg",
                                                       "uv.mean",         "smoothness.ratio",
                                                       "beauty.flip",     "count.unbracketed_rays"};
    static const std::vector<StudyDef> all = checked({
        {
            .name = "depth_range",
            .title = "Depth range",
            .question = "Far/near from 1e2 to 1e12 with the scene scaled along: where does each "
                        "depth mode (standard 24-bit, reversed float, log) start to show the far "
                        "body through the near one, or lose both (occlusion.error: the "
                        "reference's covered pixels where the real-time render shows another "
                        "body or none)?",
            .scene = "depth_range.toml",
            .xLabel = "far / near",
            .xLog = true,
            .metric = "occlusion.error",
            .columns = {"occlusion.error", "id.mismatch", "coverage.iou", "depth.rel_mean",
                        "beauty.flip", "count.unbracketed_rays"},
            .occlusionError = true,
            .points = study::depthRangePoints,
            .conclude = study::depthRangeConclude,
        },
        {
            .name = "thin_casters",
            .title = "Thin casters",
            .question = "A ring one particle thick shadows its planet: shadow-map resolution and "
                        "bias against shadow IoU, acne (false shadow) and leaks (missed shadow), "
                        "with the per-body occlusion spheres beside them.",
            .scene = "thin_casters.toml",
            .xLabel = "shadow-map resolution (texels per side)",
            .xLog = true,
            .metric = "shadow.iou",
            .columns = {"shadow.iou", "shadow.false_shadow", "shadow.missed_shadow", "beauty.flip",
                        "count.unbracketed_rays"},
            .points = study::thinCastersPoints,
            .conclude = study::thinCastersConclude,
        },
        {
            .name = "particle_size",
            .title = "Particle size on screen",
            .question = "The camera backs away from a slab from about 40 pixels per particle to "
                        "below one: SSSS's normal and uv errors and smoothness, on and off; where "
                        "does the filter radius selection stop helping?",
            .scene = "particle_size.toml",
            .xLabel = "particle diameter on screen (px)",
            .xLog = true,
            .metric = "normal.mean_deg",
            .columns = smoothingColumns,
            .points = study::particleSizePoints,
            .xOf = study::particlePixels,
            .conclude = study::particleSizeConclude,
        },
        {
            .name = "view_angle",
            .title = "View angle",
            .question = "The camera turns from face-on to grazing over a flat slab: the view "
                        "dependence of the screen-space smoothing.",
            .scene = "view_angle.toml",
            .xLabel = "view angle from the surface normal (degrees)",
            .metric = "normal.mean_deg",
            .columns = smoothingColumns,
            .points = study::viewAnglePoints,
            .conclude = study::viewAngleConclude,
        },
        {
            .name = "temporal",
            .title = "Temporal stability",
            .question = "A camera orbit in steps of half a degree: flicker as the mean "
                        "frame-to-frame ꟻLIP of the real-time renders minus the reference's.",
            .scene = "temporal.toml",
            .xLabel = "frame",
            .metric = "temporal.frame_flip",
            .columns = {"temporal.frame_flip", "temporal.reference_frame_flip", "beauty.flip",
                        "normal.mean_deg", "count.unbracketed_rays"},
            .frameToFrame = true,
            .points = study::temporalPoints,
            .conclude = study::temporalConclude,
        },
        {
            .name = "flicker",
            .title = "Flicker of the surface methods",
            .question = "Which surface method flickers least against the truth (temporal.flicker: "
                        "the real-time frames' frame-to-frame ꟻLIP minus the reference's) when "
                        "SPH particles reorder: a ball whose particles churn (a new random "
                        "displacement of up to 0.6 h each frame under a still surface), with the "
                        "default particles and with impostor spheres, and the default suite's two "
                        "real sequences, an OpenSPH impact and a LAMMPS splash, with the default "
                        "particles.",
            .scene = "",
            .xLabel = "frame",
            .metric = "temporal.flicker",
            .columns = {"temporal.flicker", "temporal.frame_flip", "temporal.reference_frame_flip",
                        "temporal.normal_flicker_deg", "normal.mean_deg", "beauty.flip",
                        "count.unbracketed_rays"},
            .frameToFrame = true,
            .points = study::flickerPoints,
            .conclude = study::flickerConclude,
        },
        {
            .name = "collision",
            .title = "Two bodies colliding",
            .question = "Two bodies from apart to overlapping: bleeding of uv and emission across "
                        "the contact, measured in a 3-pixel band along the boundary between them "
                        "in the reference.",
            .scene = "collision.toml",
            .xLabel = "gap between the surfaces (scene units; < 0 overlapping)",
            .metric = "contact.uv_mean",
            .columns = {"contact.uv_mean", "contact.emission_rmse", "contact.pixels", "uv.mean",
                        "emission.rmse", "id.mismatch", "count.unbracketed_rays"},
            .contactBand = true,
            .points = study::collisionPoints,
            .conclude = study::collisionConclude,
        },
        {
            .name = "ambient_occlusion",
            .title = "Ambient occlusion",
            .question = "The occlusion radius R from a quarter of a body's radius to ten, on a "
                        "ball resting on a slab and across two gaps the truth leaves open at "
                        "small R (a ball hanging two radii over a slab, two balls 1.35 radii "
                        "apart): where does each method, the screen-space ones (ssao, hbao, "
                        "gtao) on the shaded or the filtered depth, with or without a thickness "
                        "or a second depth layer, and rays traced against the particles' "
                        "spheres, add occlusion the traced truth does not have (ao.false), leave "
                        "out what it has (ao.missed), and come closer to it than no occlusion "
                        "(ao.mean_abs)?",
            .scene = "",
            .xLabel = "occlusion radius R (body radii)",
            .xLog = true,
            .metric = "ao.mean_abs",
            .columns = {"ao.mean_abs", "ao.false", "ao.missed", "ao.bias", "ao.halo",
                        "lighting.beauty.flip", "beauty.flip"},
            .frames = 3,
            .points = study::ambientOcclusionPoints,
            .conclude = study::ambientOcclusionConclude,
        },
        {
            .name = "emissive_light",
            .title = "Light of emitting surfaces",
            .question = "A glowing ball over a slab, moved from the middle of the view past the "
                        "screen's edge to behind the camera: the real-time estimates of the "
                        "light it casts (none, a point light per emitting body, screen-space "
                        "gathering at several directions x steps, thicknesses and blurs, in the "
                        "view and in a wider emitter target) against the reference's traced "
                        "irradiance.",
            .scene = "emissive_light.toml",
            .xLabel = "the lamp's angle from the view direction (degrees)",
            .metric = "indirect.rmse",
            .columns = {"indirect.rmse", "indirect.missed", "indirect.false", "beauty.hdrflip",
                        "beauty.flip"},
            .frames = 3,
            .points = study::emissiveLightPoints,
            .conclude = study::emissiveLightConclude,
        },
        {
            .name = "emissive_occluder",
            .title = "Light of emitting surfaces through an occluder",
            .question = "A grey disc moved between a glowing ball and the slab it lights, from "
                        "beside the ball to right under it: whether each real-time estimate "
                        "(none, a point light per emitting body, screen-space gathering) lights "
                        "what the disc shadows in the reference's traced irradiance.",
            .scene = "emissive_occluder.toml",
            .xLabel = "the disc's distance from the lamp's axis (scene units)",
            .metric = "indirect.false",
            .columns = {"indirect.rmse", "indirect.missed", "indirect.false", "beauty.hdrflip",
                        "beauty.flip"},
            .frames = 3,
            .points = study::emissiveOccluderPoints,
            .conclude = study::emissiveOccluderConclude,
        },
        {
            .name = "subpixel_emitters",
            .title = "Sub-pixel emitters",
            .question = "A glowing ball on black, the camera backing away until it is a tenth of "
                        "a pixel across, and at each size moved across a pixel frame by frame: "
                        "how much of its emitted light the real-time image keeps (flux.ratio: "
                        "its summed linear beauty over the reference's, at 16 to 16384 samples "
                        "per pixel) and how much that changes from frame to frame, drawn as "
                        "impostor spheres, with realtime.particles.min_pixels = 1 and with "
                        "realtime.particles.halo_pixels = 2.",
            .scene = "subpixel_emitters.toml",
            .xLabel = "the ball's diameter on screen (px)",
            .xLog = true,
            .metric = "flux.ratio",
            .columns = {"flux.ratio", "beauty.hdrflip", "beauty.flip", "count.unbracketed_rays"},
            .points = study::subpixelEmittersPoints,
            .xOf = study::subpixelEmitterPixels,
            .conclude = study::subpixelEmittersConclude,
        },
        {
            .name = "atmosphere",
            .title = "Atmosphere",
            .question = "A planet with a thin atmosphere, the camera backing away from just above "
                        "its limb to where it is a few pixels across: where does each real-time "
                        "end point of the view rays (the impostor depth, the filtered depth, the "
                        "analytic sphere, the seed's blend of the two by distance) give the "
                        "in-scatter closest to the reference's, which ends them at the exact "
                        "hit?",
            .scene = "atmosphere.toml",
            .xLabel = "the camera's distance from the planet's centre (planet radii)",
            .xLog = true,
            .metric = "inscatter.rmse",
            .columns = {"inscatter.rmse", "inscatter.rel", "beauty.hdrflip", "beauty.flip",
                        "count.unbracketed_rays"},
            .points = study::atmospherePoints,
            .conclude = study::atmosphereConclude,
        },
        {
            .name = "body_sphere",
            .title = "Whole-body sphere",
            .question = "A ball of 3000 particles, the camera backing away until it is about a "
                        "pixel in radius on screen, drawn as its particles and as one analytic "
                        "sphere (realtime.particles.body_sphere_pixels): below which size one "
                        "sphere matches the truth as well as the particles do (coverage IoU, "
                        "mean normal error), and the time it saves (the fastest of 3 frames).",
            .scene = "body_sphere.toml",
            .xLabel = "the ball's radius on screen (px)",
            .xLog = true,
            .metric = "coverage.iou",
            .columns = {"coverage.iou", "silhouette.mean_px", "normal.mean_deg", "beauty.flip"},
            .frames = 3,
            .points = study::bodySpherePoints,
            .xOf = study::bodySphereRadiusPixels,
            .conclude = study::bodySphereConclude,
        },
        {
            .name = "methods",
            .title = "Surface methods",
            .question = "Every surface method at its defaults and along its main parameter, with "
                        "each particle shape, on the default scenes and along particle size and "
                        "view angle: how far each is from the exact surface (normals, depth, "
                        "coverage, outlines, uv, ꟻLIP, smoothness) and what its frame costs (the "
                        "fastest of 5 frames, rendered in rounds with the other settings of its "
                        "scene after a warm-up frame).",
            .scene = "",
            .xLabel = "the method's parameter (particle radii; steps for curvature_flow); "
                      "particle_size: px per particle; view_angle: degrees",
            .metric = "normal.mean_deg",
            .columns = {"normal.mean_deg", "normal.p95_deg", "depth.rel_mean", "coverage.iou",
                        "silhouette.mean_px", "uv.mean", "beauty.flip", "smoothness.ratio",
                        "count.unbracketed_rays"},
            .frames = 5,
            .points = study::methodsPoints,
            .xOf = study::particlePixels,
            .conclude = study::methodsConclude,
        },
    });
    return all;
}

const StudyDef* findStudy(std::string_view name) {
    for (const StudyDef& d : studies())
        if (d.name == name) return &d;
    return nullptr;
}

std::string studyNames() {
    std::string names;
    for (const StudyDef& d : studies()) names += (names.empty() ? "" : ", ") + d.name;
    return names;
}

}  // namespace twinrender::app
