// Ambient occlusion end to end: the screen-space methods (realtime.ao.method) against the
// reference's traced occlusion (light.ao_radius, raymarch.ao_samples), compared by
// `twinrender run` on a ball resting on a slab (tests/scenes/ball_on_slab.toml), on a ball
// hanging over one (tests/scenes/ball_over_slab.toml) and beside another
// (tests/scenes/balls_apart.toml), where the truth is open.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/image_io.h"
#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::ambient_occlusion_test {

namespace tt = twinrender::test;
namespace fs = std::filesystem;

namespace {

const fs::path SCENES = ::twinrender::testing::sourceDir() / "tests" / "scenes";
const fs::path SCENE = SCENES / "ball_on_slab.toml";
const fs::path GAP_SCENE = SCENES / "ball_over_slab.toml";

struct AoRun {
    std::map<std::string, double> metrics;
    nlohmann::json reference;  // the reference frame's JSON (counters, timings)
};

// `twinrender run` of the scene with the --set overrides `sets`, and its reference's JSON.
AoRun runWith(const fs::path& dir, const std::string& name, const std::vector<std::string>& sets) {
    AoRun run;
    run.metrics = tt::runMetrics(SCENE, dir, name, sets);
    run.reference = tt::readJson(dir / name / "ball_on_slab" / "raymarch.json");
    return run;
}

}  // namespace

TEST(AmbientOcclusion, EachMethodLowersTheErrorAgainstNone) {
    // Without occlusion the real-time ambient is open everywhere: the crease under the ball
    // and the slab around it are too light (ao.bias > 0). Each method must come closer to the
    // traced truth. Measured (96 x 72, llvmpipe): see the bounds below, a quarter above each.
    const fs::path dir = tt::freshDir("ambient_occlusion");
    const AoRun none = runWith(dir, "none", {"realtime.ao.method=none"});
    ASSERT_TRUE(none.metrics.contains("ao.mean_abs"));
    EXPECT_GT(none.metrics.at("ao.bias"), 0.0);
    EXPECT_NEAR(none.metrics.at("ao.bias"), none.metrics.at("ao.mean_abs"), 1e-9);
    // The reference's own noise per pixel is small against the differences measured.
    const double noise = none.reference["counters"].value("ao_standard_error", 1.0);
    EXPECT_LT(noise, 0.2 * none.metrics.at("ao.mean_abs"));
    // Measured ao.mean_abs at the defaults (the filtered depth): none 0.0333, ssao 0.0227, hbao
    // 0.0225, gtao 0.0121; each bound is a quarter above the method's (and below none's).
    const std::map<std::string, double> bounds = {
        {"ssao", 1.25 * 0.0227}, {"hbao", 1.25 * 0.0225}, {"gtao", 1.25 * 0.0121}};
    EXPECT_LT(none.metrics.at("ao.mean_abs"), 1.25 * 0.0333);
    for (const auto& [method, bound] : bounds) {
        const AoRun r = runWith(dir, method, {"realtime.ao.method=" + method});
        ASSERT_TRUE(r.metrics.contains("ao.mean_abs")) << method;
        EXPECT_LT(r.metrics.at("ao.mean_abs"), none.metrics.at("ao.mean_abs")) << method;
        EXPECT_LT(r.metrics.at("ao.mean_abs"), bound) << method;
        std::printf("%s: ao.mean_abs %.4f bias %+.4f halo %.4f (none %.4f)\n", method.c_str(),
                    r.metrics.at("ao.mean_abs"), r.metrics.at("ao.bias"), r.metrics.at("ao.halo"),
                    none.metrics.at("ao.mean_abs"));
    }
}

TEST(AmbientOcclusion, HorizonMethodsInventOcclusionWhereTheTruthIsOpen) {
    // The ball hangs two of its radii over the slab, the gap wider than light.ao_radius: the
    // traced truth is open on both, and no occlusion at all is nearly exact (ao.false 0). On the
    // shaded depth the horizon methods add occlusion there, the impostors' bumps taken for
    // occluders. Measured (160 x 120, llvmpipe): ao.false none 0, hbao 0.0077, gtao 0.0212.
    const fs::path dir = tt::freshDir("ambient_occlusion_gap");
    const auto none = tt::runMetrics(GAP_SCENE, dir, "none", {"realtime.ao.method=none"});
    ASSERT_TRUE(none.contains("ao.false"));
    EXPECT_LT(none.at("ao.false"), 1e-3);
    for (const std::string method : {"hbao", "gtao"}) {
        const auto r = tt::runMetrics(GAP_SCENE, dir, method,
                                      {"realtime.ao.method=" + method, "realtime.ao.depth=shaded"});
        ASSERT_TRUE(r.contains("ao.false")) << method;
        EXPECT_GT(r.at("ao.false"), none.at("ao.false") + 4e-3) << method;
        std::printf("%s: ao.false %.4f ao.mean_abs %.4f (none %.4f, %.4f)\n", method.c_str(),
                    r.at("ao.false"), r.at("ao.mean_abs"), none.at("ao.false"),
                    none.at("ao.mean_abs"));
    }
}

TEST(AmbientOcclusion, HbaoAtTheDefaultsStaysWithinTheFalseOcclusionBoundAcrossAGap) {
    // The default depth of the occlusion pass is the filtered one (docs/lighting.md: the
    // ambient_occlusion study measures it better than the shaded on every scene for each
    // method). On it hbao, the screen-space method docs/lighting.md finds within the bound, adds
    // less than 0.005 of occlusion where the truth is open, over the slab and beside the other
    // ball. Measured (160 x 120, llvmpipe): ao.false 0.0010 over the slab, 0.0013 beside the ball.
    const fs::path dir = tt::freshDir("ambient_occlusion_default");
    for (const fs::path& scene : {GAP_SCENE, SCENES / "balls_apart.toml"}) {
        const auto r =
            tt::runMetrics(scene, dir, scene.stem().string(), {"realtime.ao.method=hbao"});
        ASSERT_TRUE(r.contains("ao.false")) << scene;
        EXPECT_LT(r.at("ao.false"), 0.005) << scene;
        std::printf("%s: hbao ao.false %.4f ao.mean_abs %.4f\n", scene.stem().c_str(),
                    r.at("ao.false"), r.at("ao.mean_abs"));
    }
}

TEST(AmbientOcclusion, ASecondLayerEndsAHangingBallAtItsBack) {
    // R reaches past the gap under the hanging ball (1.6, four of its radii): the depth buffer
    // holds the ball's front, and gtao takes all behind it for a wall down to the slab, further
    // from the truth than no occlusion. The second depth layer (realtime.ao.layers = 2) ends the
    // ball at its back; the gap under it is open again. Measured (160 x 120, llvmpipe):
    // ao.mean_abs none 0.0714, gtao 0.0981, gtao with the layer 0.0338. The bounds: below none's
    // by a quarter of it, and below gtao's without the layer by half of it.
    const fs::path dir = tt::freshDir("ambient_occlusion_layer");
    const std::string reach = "light.ao_radius=1.6";
    const auto none = tt::runMetrics(GAP_SCENE, dir, "none", {reach, "realtime.ao.method=none"});
    const auto front = tt::runMetrics(GAP_SCENE, dir, "front", {reach, "realtime.ao.method=gtao"});
    const auto layered = tt::runMetrics(GAP_SCENE, dir, "layered",
                                        {reach, "realtime.ao.method=gtao", "realtime.ao.layers=2"});
    ASSERT_TRUE(none.contains("ao.mean_abs") && front.contains("ao.mean_abs") &&
                layered.contains("ao.mean_abs"));
    EXPECT_GT(front.at("ao.mean_abs"), none.at("ao.mean_abs"));
    EXPECT_LT(layered.at("ao.mean_abs"), 0.75 * none.at("ao.mean_abs"));
    EXPECT_LT(layered.at("ao.mean_abs"), 0.5 * front.at("ao.mean_abs"));
    std::printf("ao.mean_abs none %.4f, gtao %.4f, with the second layer %.4f\n",
                none.at("ao.mean_abs"), front.at("ao.mean_abs"), layered.at("ao.mean_abs"));
}

// realtime.ao.method = "traced" on the shaded depth (docs/lighting.md: the filtered depth rounds
// the surface off at the image's border, which the rays then start below).
const std::vector<std::string> TRACED = {"realtime.ao.method=traced", "realtime.ao.depth=shaded"};

std::vector<std::string> with(std::vector<std::string> sets, const std::string& more) {
    sets.push_back(more);
    return sets;
}

TEST(AmbientOcclusion, TracedComesClosestWhereTheTruthIsOccluded) {
    // Rays against the particles' spheres see what the depth buffer hides: the slab under the
    // hanging ball (R 1.6, four of its radii) and the crease under the resting one. Measured
    // (llvmpipe) ao.mean_abs: ball_over_slab at R 1.6 none 0.0714, hbao 0.0397, gtao 0.0981,
    // traced 0.0150; ball_on_slab at R 0.3 none 0.0333, hbao 0.0225, gtao 0.0121, traced 0.0047.
    // Bounds a quarter above traced's; it must also be below none's and below the best
    // screen-space method's there (hbao over the slab, gtao on it), run alongside.
    const fs::path dir = tt::freshDir("ambient_occlusion_traced");
    const struct {
        fs::path scene;
        std::vector<std::string> sets;
        double bound;
        std::string best;
    } cases[] = {{GAP_SCENE, {"light.ao_radius=1.6"}, 1.25 * 0.0150, "hbao"},
                 {SCENE, {}, 1.25 * 0.0047, "gtao"}};
    for (const auto& c : cases) {
        const std::string name = c.scene.stem().string();
        const auto none =
            tt::runMetrics(c.scene, dir, name + "_none", with(c.sets, "realtime.ao.method=none"));
        const auto best = tt::runMetrics(c.scene, dir, name + "_" + c.best,
                                         with(c.sets, "realtime.ao.method=" + c.best));
        const auto traced = tt::runMetrics(c.scene, dir, name + "_traced",
                                           with(with(c.sets, TRACED[0]), TRACED[1]));
        ASSERT_TRUE(traced.contains("ao.mean_abs")) << name;
        EXPECT_LT(traced.at("ao.mean_abs"), c.bound) << name;
        EXPECT_LT(traced.at("ao.mean_abs"), none.at("ao.mean_abs")) << name;
        EXPECT_LT(traced.at("ao.mean_abs"), best.at("ao.mean_abs")) << name;
        std::printf(
            "%s: traced ao.mean_abs %.4f ao.false %.4f ao.missed %.4f (none %.4f, %s "
            "%.4f)\n",
            name.c_str(), traced.at("ao.mean_abs"), traced.at("ao.false"), traced.at("ao.missed"),
            none.at("ao.mean_abs"), c.best.c_str(), best.at("ao.mean_abs"));
    }
}

TEST(AmbientOcclusion, TracedAddsNoOcclusionAcrossAGapAndIsTheSameTwice) {
    // Where the truth is open (the gap under the hanging ball wider than R 0.2, the balls
    // apart at R 0.3) the rays meet nothing: an open flat slab and the balls' own bumps stay
    // open. Measured (llvmpipe): ao.false 0.0002 over the slab, 0.0009 beside the ball; the
    // bound is the goal's, 0.005. The rays' directions come from the pixel alone: the same
    // occlusion channel twice.
    const fs::path dir = tt::freshDir("ambient_occlusion_traced_open");
    for (const fs::path& scene : {GAP_SCENE, SCENES / "balls_apart.toml"}) {
        const auto r = tt::runMetrics(scene, dir, scene.stem().string(), TRACED);
        ASSERT_TRUE(r.contains("ao.false")) << scene;
        EXPECT_LT(r.at("ao.false"), 0.005) << scene;
        std::printf("%s: traced ao.false %.4f ao.mean_abs %.4f\n", scene.stem().c_str(),
                    r.at("ao.false"), r.at("ao.mean_abs"));
    }
    tt::runMetrics(GAP_SCENE, dir, "again", TRACED);
    const auto ao = [&](const std::string& name) {
        const core::Image image = core::readImage(dir / name / "ball_over_slab" / "realtime.exr");
        const int c = image.channelIndex("ao");
        std::vector<float> values;
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x) values.push_back(image.at(x, y, c));
        return values;
    };
    const std::vector<float> first = ao("ball_over_slab"), second = ao("again");
    ASSERT_FALSE(first.empty());
    EXPECT_TRUE(first == second);
}

TEST(AmbientOcclusion, GtaosAngleBiasKeepsAnOpenSlabOpen) {
    // Over the slab at R 0.2 the truth is open. On the filtered depth, gtao as published
    // (realtime.ao.gtao_angle_bias = 0) takes the bumps the filter leaves for horizons; its
    // default bias of 10 degrees counts none within it of the tangent plane. Measured (160 x
    // 120, llvmpipe): ao.false 0.0065 without the bias, 0.0016 with it. The bound: a half of
    // the unbiased value, and the goal's 0.005.
    const fs::path dir = tt::freshDir("ambient_occlusion_gtao_bias");
    const auto published = tt::runMetrics(
        GAP_SCENE, dir, "published", {"realtime.ao.method=gtao", "realtime.ao.gtao_angle_bias=0"});
    const auto biased = tt::runMetrics(GAP_SCENE, dir, "biased", {"realtime.ao.method=gtao"});
    ASSERT_TRUE(published.contains("ao.false") && biased.contains("ao.false"));
    EXPECT_LT(biased.at("ao.false"), 0.5 * published.at("ao.false"));
    EXPECT_LT(biased.at("ao.false"), 0.005);
    std::printf("gtao ao.false %.4f without the angle bias, %.4f with it\n",
                published.at("ao.false"), biased.at("ao.false"));
}

TEST(AmbientOcclusion, TheDefaultsAddNoOcclusionWhereTheImagesEdgeCutsTheSlab) {
    // The defaults: the traced rays from the filtered depth. The image's edge cuts the slab; a
    // narrow-range filter that read outside the image as background rounded the slab off
    // there, and the rays then started under it (ao.false 0.0144 over the slab at R 0.2).
    // Measured with the filter dropping those samples: 0.0001. The bound is the goal's.
    const fs::path dir = tt::freshDir("ambient_occlusion_edge");
    const auto r = tt::runMetrics(GAP_SCENE, dir, "defaults", {});
    ASSERT_TRUE(r.contains("ao.false"));
    EXPECT_LT(r.at("ao.false"), 0.005);
    std::printf("defaults: ao.false %.4f ao.mean_abs %.4f\n", r.at("ao.false"),
                r.at("ao.mean_abs"));
}

}  // namespace twinrender::e2e::ambient_occlusion_test
