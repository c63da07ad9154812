// Several renderers measured against one reference in one run (`run --test realtime --test
// realtime:KEY=VALUE --test external`, app/test_renderers.h): each held to the bounds, side by
// side on the scene's page, and a renderer that fails a bound fails the scene, in the verdict,
// JUnit and summary.md.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "tests/analytic_sphere.h"
#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::test_renderers_test {

namespace tt = twinrender::test;
namespace fs = std::filesystem;

namespace {

// The built-in renderer with settings of its own: no surface smoothing.
const std::string UNSMOOTHED = "realtime:realtime.surface.method=none";

}  // namespace

TEST(TestRenderers, RunMeasuresSeveralSideBySideEachHeldToTheBounds) {
    const fs::path dir = tt::freshDir("test_renderers");
    // The built-in renderer's SSIM on the sphere is about 0.99; the analytic renderer shades with
    // Lambert alone (about 0.83).
    tt::writeFile(dir / "bounds.toml",
                  "\"coverage.iou\" = { min = 0.999 }\n\"beauty.ssim\" = { min = 0.9 }\n");
    const std::string run = "run " + tt::SPHERE + " --thresholds " +
                            (dir / "bounds.toml").string() + " --external-command '" + tt::ADAPTER +
                            "' --test realtime --test " + UNSMOOTHED + " --test external";
    const auto r = tt::runTwinrender(run + " --junit " + (dir / "junit.xml").string() + " --out " +
                                     (dir / "out").string());
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("  + external"), std::string::npos) << r.output;
    const nlohmann::json m = tt::readJson(dir / "out" / "one_sphere" / "metrics.json");
    ASSERT_EQ(m["tests"].size(), 3u) << m;
    EXPECT_EQ(m["tests"][0]["name"], "realtime");
    EXPECT_EQ(m["tests"][1]["name"], UNSMOOTHED);
    EXPECT_EQ(m["tests"][2]["name"], "external");
    // The scene's own metrics are the first renderer's.
    EXPECT_TRUE(m["metrics"].contains("time.realtime_ms"));
    EXPECT_EQ(m["metrics"]["normal.mean_deg"], m["tests"][0]["metrics"]["normal.mean_deg"]);
    // Its own settings: another surface, other normals.
    EXPECT_NE(m["tests"][1]["metrics"]["normal.mean_deg"], m["metrics"]["normal.mean_deg"]);
    EXPECT_TRUE(fs::exists(dir / "out" / "one_sphere" / "tests" /
                           "realtime_realtime.surface.method_none" / "realtime.exr"));
    EXPECT_EQ(m["tests"][2]["metrics"]["coverage.iou"], 1.0);
    EXPECT_LT(m["tests"][2]["metrics"]["beauty.ssim"].get<double>(), 0.9);
    // The second renderer's failed bound, named by the renderer, fails the scene.
    bool named = false;
    for (const auto& c : m["checks"]) named |= c["metric"] == "external:beauty.ssim";
    EXPECT_TRUE(named) << m["checks"];
    EXPECT_EQ(m["status"], "fail");
    EXPECT_NE(tt::readText(dir / "junit.xml").find("name=\"external:beauty.ssim\""),
              std::string::npos);
    EXPECT_NE(tt::readText(dir / "out" / "summary.md").find("external:beauty.ssim"),
              std::string::npos);
    // One table on the scene's page, a column per renderer, its images in its own folder.
    const std::string page = tt::readText(dir / "out" / "one_sphere" / "index.html");
    EXPECT_NE(page.find("<h2>Test renderers</h2>"), std::string::npos);
    EXPECT_NE(page.find("src=\"tests/external/external.beauty.png\""), std::string::npos);
    EXPECT_TRUE(fs::exists(dir / "out" / "one_sphere" / "tests" / "external" / "external.exr"));

    const auto twice =
        tt::runTwinrender(run + " --test external --out " + (dir / "twice").string());
    EXPECT_EQ(twice.exitCode, 4) << twice.output;
    EXPECT_NE(twice.output.find("--test external is given twice"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "twice"));
    // Settings of its own are the real-time renderer's: the reference is the same for all.
    const auto other = tt::runTwinrender(
        "run " + tt::SPHERE + " --test realtime:camera.width=32 --out " + (dir / "other").string());
    EXPECT_EQ(other.exitCode, 4) << other.output;
    EXPECT_NE(other.output.find("is not a realtime.KEY=VALUE setting"), std::string::npos);
}

}  // namespace twinrender::e2e::test_renderers_test
