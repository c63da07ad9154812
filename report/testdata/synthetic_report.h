// A small report made without any renderer, for the report tests (report/*_test.cpp)
// and the browser test (tests/report_browser_test.cpp): two scenes of tiny AOV images (a lit
// sphere of two bodies; the "real-time" one slightly larger and shifted), their buffer PNGs
// and ꟻLIP and HDR-ꟻLIP maps written into the report folder, metrics (the error split among
// them, emission.rmse not applicable), checks against thresholds and a baseline, timings (a
// stage that did not run among them) and settings.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "compare/baseline.h"
#include "compare/colour_map.h"
#include "compare/flip.h"
#include "compare/hdr_flip.h"
#include "compare/testdata/synthetic_aov.h"
#include "compare/thresholds.h"
#include "core/frame.h"
#include "core/image.h"
#include "core/image_io.h"
#include "report/buffer_display.h"
#include "report/report.h"

namespace twinrender::report::testdata {

using compare::Baseline;
using compare::compareToBaseline;
using compare::evaluate;
using compare::flip;
using compare::FlipResult;
using compare::hdrFlip;
using compare::HdrFlipResult;
using compare::MetricValues;
using compare::Thresholds;
using compare::writeErrorMapPng;
using compare::testdata::syntheticAov;

// One scene of the synthetic report: images written under dir/<name>/.
inline SceneReport syntheticScene(const std::filesystem::path& dir, const std::string& name,
                                  double shift, const Thresholds& thresholds,
                                  const Baseline* baseline) {
    const int w = 64, h = 40;
    const core::Image ref = syntheticAov(w, h, 32.0, 20.0, 15.0);
    const core::Image test = syntheticAov(w, h, 32.0 + shift, 20.0, 15.0 + 0.5 * shift);
    const std::filesystem::path sceneDir = dir / name;
    BufferVisualSettings vis;
    vis.depthRange = depthRange(ref, test);

    SceneReport s;
    s.name = name;
    s.description =
        fmt::format("A synthetic sphere of two bodies, the real-time one shifted by {} px", shift);
    s.renderers["raymarch"].images = writeBufferImages(ref, nullptr, sceneDir, "raymarch", vis);
    s.renderers["realtime"].images = writeBufferImages(test, nullptr, sceneDir, "realtime", vis);
    // The raw files `run` writes beside the PNGs, which the scene page links.
    for (const char* r : {"raymarch", "realtime"}) {
        core::writeImage(std::string(r) == "raymarch" ? ref : test,
                         sceneDir / (std::string(r) + ".exr"));
        core::writeTextFile(sceneDir / (std::string(r) + ".json"), "{}\n");
    }
    const FlipResult f =
        flip(core::tonemappedBeauty(ref, 1.0f), core::tonemappedBeauty(test, 1.0f));
    writeErrorMapPng(f.errorMap, 0, 0.0, 1.0, sceneDir / "flip.png");
    s.errorMaps["beauty"] = {"flip.png", "ꟻLIP error", 0.0, 1.0, ""};
    const HdrFlipResult hdr = hdrFlip(ref, test);
    writeErrorMapPng(hdr.errorMap, 0, 0.0, 1.0, sceneDir / "hdrflip.png");
    s.errorMaps["beauty.hdrflip"] = {"hdrflip.png", "HDR-ꟻLIP error", 0.0, 1.0, ""};

    s.metrics = {{"beauty.psnr", 30.0 - 4.0 * shift},
                 {"beauty.ssim", 0.98 - 0.02 * shift},
                 {"beauty.flip", f.mean},
                 {"coverage.iou", 1.0 - 0.03 * shift},
                 {"normal.mean_deg", 1.5 + 2.0 * shift},
                 {"shadow.iou", 0.95 - 0.1 * shift},
                 {"emission.rmse", 0.0},
                 {"surface.beauty.flip", 0.8 * f.mean},
                 {"lighting.beauty.flip", 0.15 * f.mean},
                 {"shading.beauty.flip", 1e-5},
                 {"time.realtime_ms", 2.5},
                 {"time.raymarch_ms", 850.0}};
    s.notApplicable["emission.rmse"] = "neither render has any emission";
    s.checks = evaluate(s.metrics, thresholds.forScene(name));
    if (baseline) {
        const nlohmann::json settings = {{"realtime", {{"ssss", {{"enabled", shift < 1.0}}}}}};
        auto b = compareToBaseline(name, s.metrics, *baseline, &settings);
        s.checks.insert(s.checks.end(), b.begin(), b.end());
        if (const MetricValues* m = baseline->metrics(name)) s.baseline = *m;
    }
    s.renderers["realtime"].timingsMs = {{"total", 2.5}, {"shadow", 0.3}, {"gbuffer", 0.8},
                                         {"ssss", 0.9},  {"shade", 0.3},  {"post", 0.2},
                                         {"ao", 0.0}};
    s.renderers["realtime"].device = "llvmpipe (LLVM 15.0.6, 256 bits)";
    s.renderers["raymarch"].timingsMs = {{"total", 850.0}, {"build", 12.0}, {"trace", 838.0}};
    s.renderers["raymarch"].device = "2 CPU threads";
    s.renderers["raymarch"].counters = {{"unbracketed_rays", 0.0}};
    s.settings = {
        {"realtime", {{"ssss", {{"enabled", shift < 1.0}, {"separable", true}}}, {"depth", "log"}}},
        {"raymarch", {{"level", 0.13}}},
        {"camera", {{"width", w}, {"height", h}}},
        {"compare",
         {{"hdrflip",
           {{"start_exposure", hdr.range.start},
            {"stop_exposure", hdr.range.stop},
            {"exposures", hdr.range.count}}}}}};
    return s;
}

// A scene without images: beauty.flip beyond its max and its baseline, coverage.iou bounded
// but not computed, shadow.iou between its min and warn_min; timings of both renderers.
inline SceneReport sceneWithChecks() {
    SceneReport s;
    s.name = "planet";
    s.metrics = {{"beauty.psnr", std::numeric_limits<double>::infinity()},
                 {"beauty.flip", 0.2},
                 {"shadow.iou", 0.97}};
    const Thresholds t = Thresholds::parseString(
        "\"beauty.flip\" = { max = 0.15 }\n\"shadow.iou\" = { min = 0.9, warn_min = 0.98 }\n"
        "\"coverage.iou\" = { min = 0.9 }\n",
        "t.toml");
    s.checks = evaluate(s.metrics, t.global());
    Baseline b;
    b.scenes["planet"].metrics = {{"beauty.flip", 0.1}};
    const auto bc = compareToBaseline("planet", s.metrics, b);
    s.checks.insert(s.checks.end(), bc.begin(), bc.end());
    s.renderers["realtime"].timingsMs = {{"total", 4.0}, {"ssss", 1.5}};
    s.renderers["raymarch"].timingsMs = {{"total", 400.0}};
    return s;
}

// Two scenes: "sphere" (pass) and "sphere_shifted" (fails its shadow.iou bound and its
// baseline), written into dir.
inline RunReport syntheticReport(const std::filesystem::path& dir) {
    const Thresholds thresholds = Thresholds::parseString(R"(
"beauty.psnr" = { min = 20, warn_min = 25 }
"beauty.flip" = { max = 0.5, warn_max = 0.3 }
"coverage.iou" = { min = 0.9 }
"shadow.iou" = { min = 0.9 }
)",
                                                          "thresholds.toml");
    Baseline baseline;
    baseline.file = "baseline.json";
    baseline.scenes["sphere_shifted"].metrics = {
        {"beauty.psnr", 29.0}, {"shadow.iou", 0.95}, {"time.realtime_ms", 2.0}};
    baseline.scenes["sphere_shifted"].settings = {{"realtime", {{"ssss", {{"enabled", true}}}}}};
    RunReport run;
    run.createdAt = "2024-01-01 00:00 UTC";
    run.commandLine = "twinrender run scenes --out " + dir.string();
    run.thresholdsFile = "thresholds.toml";
    run.baselineFile = "baseline.json";
    run.scenes.push_back(syntheticScene(dir, "sphere", 0.0, thresholds, &baseline));
    run.scenes.push_back(syntheticScene(dir, "sphere_shifted", 1.5, thresholds, &baseline));
    return run;
}

}  // namespace twinrender::report::testdata
