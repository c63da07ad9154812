// The stability studies (docs/studies.md): each one a small scene of scenes/studies/, a list of
// settings points (series, x, the overrides that make them) and the conclusion drawn from the
// measured rows: the chart and a one-line finding, both computed from the data.
#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "app/render_job.h"
#include "report/study_report.h"

namespace twinrender::app {

struct StudyPoint {
    std::string series;             // the chart's line this point belongs to
    double x = NAN;                 // NaN: StudyDef::xOf computes it from the loaded scene
    std::vector<std::string> sets;  // KEY=VALUE overrides, applied after the user's --set
    // A scene of its own, relative to scenes/studies/ ("../planet.toml" is a default scene),
    // for a study that spans several; its rows then name their scene. Empty: StudyDef::scene.
    std::string scene;
    // A repeat of another point (app/studies/common.h repeatOf): rendered with the camera turned
    // right by half a pixel, an override of camera.target set from the loaded scene's own camera
    // (x is the unturned camera's). How much a metric moves with where the pixel grid falls:
    // the noise that a study's ties rest on.
    bool turnHalfPixel = false;
};

struct StudyDef {
    std::string name;      // "depth_range": the CLI name, the output folder
    std::string title;     // "Depth range"
    std::string question;  // one sentence: what it measures and how
    std::string scene;     // file name in scenes/studies/; "" when every point names its own
    std::string xLabel;    // with its unit
    bool xLog = false;
    std::string metric;                // the chart's y
    std::vector<std::string> columns;  // metrics in the page's table
    // Also measure bleeding in the band around the contact of two bodies
    // (contact.uv_mean, contact.emission_rmse, contact.pixels; compare/contact_band.h).
    bool contactBand = false;
    // Also measure occlusion.error: the fraction of the reference's covered pixels where the
    // real-time render shows another body or none (id.mismatch counts only pixels covered in
    // both, so it cannot see bodies that vanish).
    bool occlusionError = false;
    // The points of one series are consecutive frames: each row also gets its change from the
    // previous one of its series against the truth (compare/temporal_error.h: temporal.flicker,
    // temporal.frame_flip, temporal.reference_frame_flip and the normals' change).
    bool frameToFrame = false;
    // Real-time frames rendered per point: 1, the first frame of a renderer (the studies of
    // stability); more, an untimed warm-up frame and then this many, in rounds with the other
    // points of the scene, for a study that compares costs: a point's time per stage is then
    // the fastest of its frames (app/render_job.h renderTimedRounds). Quick runs time one
    // frame (after the warm-up).
    int frames = 1;
    std::function<std::vector<StudyPoint>(bool quick)> points;
    std::function<double(const LoadedScene&)> xOf = nullptr;  // for points without an x
    // Fills finding, facts and chart from the rows (and the fields above).
    std::function<void(report::StudyResult&)> conclude;
};

// Every study, in the order `twinrender study` runs them (app/studies/registry.cpp; each study's
// points and conclusion are in app/studies/<name>.cpp).
const std::vector<StudyDef>& studies();

// The study of that name; nullptr when there is none.
const StudyDef* findStudy(std::string_view name);

// Every study's name in that order, as a list for people: "depth_range, thin_casters, ...".
std::string studyNames();

}  // namespace twinrender::app
