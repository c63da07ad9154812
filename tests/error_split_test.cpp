// The error split end to end (core::Frame::split, docs/design.md "The error split"): `twinrender
// run` shades the reference's surface and light with the real-time shader, and each part's
// image metrics say where the real-time image's error comes from.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::error_split_test {

namespace tt = twinrender::test;
namespace fs = std::filesystem;

namespace {

const fs::path SCENE =
    ::twinrender::testing::sourceDir() / "tests" / "scenes" / "ball_on_slab.toml";

std::map<std::string, double> metricsOf(const fs::path& dir, const std::string& name,
                                        const std::vector<std::string>& sets) {
    return tt::runMetrics(SCENE, dir, name, sets);
}

}  // namespace

TEST(ErrorSplit, EachPartVanishesWhereTheExactOneStandsIn) {
    // The reference's own surface and light through the real-time shader ("shading") is the
    // reference up to the two shaders' rounding: measured ꟻLIP 4.6e-6, PSNR 152 dB. Turning the
    // real-time shadows off moves the lighting part (0.0088 -> 0.032 measured) and leaves the
    // surface part, which takes the reference's light, exactly as it was (0.00354 both).
    const fs::path dir = tt::freshDir("error_split");
    const auto lit = metricsOf(dir, "map", {"realtime.ao.method=gtao"});
    const auto dark = metricsOf(dir, "none", {"realtime.ao.method=gtao", "realtime.shadows=none"});
    for (const auto* m : {&lit, &dark})
        for (const char* key : {"surface.beauty.flip", "lighting.beauty.flip",
                                "shading.beauty.flip", "surface.beauty.psnr"})
            ASSERT_TRUE(m->contains(key)) << key;
    EXPECT_LT(lit.at("shading.beauty.flip"), 1e-4);
    EXPECT_GT(lit.at("shading.beauty.psnr"), 80.0);
    EXPECT_EQ(lit.at("surface.beauty.flip"), dark.at("surface.beauty.flip"));
    EXPECT_GT(dark.at("lighting.beauty.flip"), 2.0 * lit.at("lighting.beauty.flip"));
    EXPECT_GT(dark.at("beauty.flip"), lit.at("beauty.flip"));
    // Each part is an error of its own: above the floor, below the whole.
    for (const char* part : {"surface", "lighting"}) {
        const std::string key = std::string(part) + ".beauty.flip";
        EXPECT_GT(lit.at(key), 10.0 * lit.at("shading.beauty.flip")) << key;
        EXPECT_LT(lit.at(key), lit.at("beauty.flip")) << key;
    }
}

}  // namespace twinrender::e2e::error_split_test
