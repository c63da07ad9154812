// `twinrender compare` with a test image that carries some AOV channels, as another renderer
// writes them (beauty, coverage, depth, normals): every metric those channels give, the rest
// "not provided" (never a value, never a pass, no bound applies), and `--scene`, which gives the
// comparison the scene's exposure and light as `run` has them.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/image_io.h"
#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::compare_partial_test {

namespace tt = twinrender::test;
namespace fs = std::filesystem;

namespace {

const std::string PLANET = ::twinrender::testing::sourceDir().string() + "/scenes/planet.toml";
const std::string SMALL = " --set camera.width=96 --set camera.height=72";

// The planet's two renders, the real-time one also as a partial AOV image.
struct Renders {
    std::string reference, full, partial;
};
Renders renders(const fs::path& dir) {
    const auto r =
        tt::runTwinrender("render " + PLANET + " --renderer both --out " + dir.string() + SMALL);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    const fs::path full = dir / "planet" / "realtime.exr";
    const std::vector<std::string> some = {"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z"};
    twinrender::core::writeImage(twinrender::core::readImage(full).select(some),
                                 dir / "partial.exr");
    return {(dir / "planet" / "raymarch.exr").string(), full.string(),
            (dir / "partial.exr").string()};
}

}  // namespace

TEST(CompareCommand, APartialAovImageGetsTheMetricsItsChannelsGive) {
    const fs::path dir = tt::freshDir("compare_partial");
    const Renders images = renders(dir);
    // A bound on a metric the image does not provide (shadow.iou) does not apply; one on a
    // metric it does (depth.rel_mean) is checked.
    tt::writeFile(dir / "bounds.toml",
                  "\"shadow.iou\" = { min = 0.99 }\n\"depth.rel_mean\" = { max = 1.0 }\n");
    const auto r = tt::runTwinrender(
        "compare " + images.reference + " " + images.partial + " --scene " + PLANET + SMALL +
        " --thresholds " + (dir / "bounds.toml").string() + " --out " + (dir / "c").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("shadow.iou                 not provided"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("not provided: the images lack uv.U"), std::string::npos) << r.output;
    const nlohmann::json m = tt::readJson(dir / "c" / "metrics.json");
    for (const char* key : {"coverage.iou", "depth.rel_mean", "normal.mean_deg", "beauty.flip"})
        EXPECT_TRUE(m["metrics"].contains(key)) << key;
    for (const char* key : {"shadow.iou", "uv.mean", "id.mismatch", "emission.rmse"}) {
        EXPECT_FALSE(m["metrics"].contains(key)) << key;
        const auto& list = m["not_provided"];
        EXPECT_NE(std::find(list.begin(), list.end(), key), list.end()) << key;
    }
    // The check that applies: depth.rel_mean, and only it.
    ASSERT_EQ(m["checks"].size(), 1u) << m["checks"];
    EXPECT_EQ(m["checks"][0]["metric"], "depth.rel_mean");
    // The same channels of the full image measure the same: coverage and depth.
    const auto full =
        tt::runTwinrender("compare " + images.reference + " " + images.full + " --scene " + PLANET +
                          SMALL + " --out " + (dir / "f").string());
    ASSERT_EQ(full.exitCode, 0) << full.output;
    const nlohmann::json f = tt::readJson(dir / "f" / "metrics.json");
    EXPECT_EQ(m["metrics"]["coverage.iou"], f["metrics"]["coverage.iou"]);
    EXPECT_EQ(m["metrics"]["beauty.flip"], f["metrics"]["beauty.flip"]);
    EXPECT_FALSE(f.contains("not_provided"));
}

TEST(CompareCommand, TheSceneGivesTheExposureAndLightOfRun) {
    const fs::path dir = tt::freshDir("compare_scene");
    const Renders images = renders(dir);
    auto flip = [&](const std::string& args, const std::string& out) {
        const auto r = tt::runTwinrender("compare " + images.reference + " " + images.full + args +
                                         " --out " + (dir / out).string());
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return tt::readJson(dir / out / "metrics.json")["metrics"];
    };
    const nlohmann::json plain = flip("", "plain");
    const nlohmann::json scene = flip(" --scene " + PLANET + SMALL, "scene");
    const nlohmann::json brighter =
        flip(" --scene " + PLANET + SMALL + " --set camera.exposure=4", "brighter");
    // The exposure reaches the tonemapped beauty: another exposure, another ꟻLIP.
    EXPECT_NE(scene["beauty.flip"], brighter["beauty.flip"]);
    // The light reaches the shadow metrics' mask (facing the light), which without a scene is
    // every pixel covered in both.
    EXPECT_NE(plain["shadow.iou"], scene["shadow.iou"]);
    // What `run` measured for the planet's pair is what `compare --scene` measures.
    tt::writeFile(dir / "none.toml", "# no bounds\n");
    const auto run =
        tt::runTwinrender("run " + PLANET + SMALL + " --out " + (dir / "run").string() +
                          " --thresholds " + (dir / "none.toml").string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const nlohmann::json measured =
        tt::readJson(dir / "run" / "planet" / "metrics.json")["metrics"];
    for (const char* key : {"beauty.flip", "shadow.iou", "normal.mean_deg"})
        EXPECT_EQ(measured[key], scene[key]) << key;
}

}  // namespace twinrender::e2e::compare_partial_test
