// The render command end to end: the AOV EXR, the PNG and the JSON of docs/design.md.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/frame.h"
#include "core/image_io.h"
#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::render_test {

namespace tt = twinrender::test;

TEST(RenderCommand, WritesTheAovExrPngAndJson) {
    const auto dir = tt::freshDir("render_command");
    const auto r =
        tt::runTwinrender(std::string("render ") + ::twinrender::testing::sourceDir().string() +
                          "/scenes/planet.toml --renderer raymarch --out " + dir.string() +
                          " --set camera.width=48 --set camera.height=36 --threads 2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const auto exr = twinrender::core::readImage(dir / "planet" / "raymarch.exr");
    EXPECT_EQ(exr.width(), 48);
    EXPECT_EQ(exr.height(), 36);
    for (const auto& name : twinrender::core::aov::channelNames())
        EXPECT_TRUE(exr.hasChannel(name)) << name;
    const auto png = twinrender::core::readImage(dir / "planet" / "raymarch.png");
    EXPECT_EQ(png.width(), 48);
    // Background: id -1, Z infinite; the planet in the middle: id 0, finite depth.
    EXPECT_EQ(exr.at(0, 0, exr.channelIndex("id")), -1.0f);
    EXPECT_TRUE(std::isinf(exr.at(0, 0, exr.channelIndex("Z"))));
    EXPECT_EQ(exr.at(24, 18, exr.channelIndex("id")), 0.0f);
    EXPECT_NEAR(exr.at(24, 18, exr.channelIndex("Z")), 4.36 - 1.0, 0.1);  // distance - radius
    std::ifstream in(dir / "planet" / "raymarch.json");
    const auto j = nlohmann::json::parse(in);
    EXPECT_EQ(j["renderer"], "raymarch");
    EXPECT_GT(j["timings_ms"]["total"].get<double>(), 0.0);
    EXPECT_TRUE(j["timings_ms"].contains("build"));
    EXPECT_TRUE(j["timings_ms"].contains("trace"));
    EXPECT_EQ(j["counters"]["unbracketed_rays"].get<double>(), 0.0);
    EXPECT_EQ(j["settings"]["raymarch.surface_level"].get<double>(), 0.13);
    EXPECT_GT(j["particle_count"].get<int>(), 15000);
    // No temporary file is left behind.
    EXPECT_EQ(tt::countFiles(dir / "planet"), 3u);
}

// The example pass-through surface shader shipped in examples/ renders what
// realtime.surface.method = "none" renders, bit for bit.
TEST(RenderCommand, PassThroughExampleShaderEqualsNone) {
    const auto dir = tt::freshDir("pass_through_shader");
    auto render = [&](const std::string& name, const std::string& set) {
        const auto r = tt::runTwinrender(
            std::string("render ") + ::twinrender::testing::sourceDir().string() +
            "/scenes/planet.toml --renderer realtime --out " + (dir / name).string() +
            " --set camera.width=64 --set camera.height=48 " + set);
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return twinrender::core::readImage(dir / name / "planet" / "realtime.exr");
    };
    const auto none = render("none", "--set realtime.surface.method=none");
    const auto pass = render("pass", std::string("--set realtime.surface.shader=") +
                                         ::twinrender::testing::sourceDir().string() +
                                         "/examples/surface_pass_through.glsl");
    EXPECT_TRUE(none == pass);
    EXPECT_EQ(tt::readText(dir / "none" / "planet" / "realtime.png"),
              tt::readText(dir / "pass" / "planet" / "realtime.png"));
}

}  // namespace twinrender::e2e::render_test
