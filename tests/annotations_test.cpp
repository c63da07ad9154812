// CI annotations end to end: `run` and `merge` print GitHub's ::error and ::warning lines for
// the checks that did not pass when asked to, or when the environment is GitHub Actions, and
// not otherwise. One small scene (64x48, 1500 particles) held to bounds it cannot meet.
#include <gtest/gtest.h>

#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::annotations_test {

namespace tt = twinrender::test;
namespace fs = std::filesystem;
using tt::count;

namespace {

const std::string SOURCE = ::twinrender::testing::sourceDir().string();
const std::string PLANET = SOURCE +
                           "/scenes/planet.toml --set camera.width=64 --set "
                           "camera.height=48 --set bodies.planet.particles=1500";

}  // namespace

TEST(Annotations, GithubLinesWhenAskedOrOnGithubActionsOnly) {
    const fs::path dir = tt::freshDir("annotations");
    const fs::path bounds = dir / "thresholds.toml";
    tt::writeFile(bounds,
                  "\"beauty.flip\" = { max = 1e-4 }\n\"beauty.ssim\" = { warn_min = 0.99999 }\n");
    const std::string run = "run " + PLANET + " --thresholds " + bounds.string();
    const std::string onGithub = "GITHUB_ACTIONS=true GITHUB_WORKSPACE=" + SOURCE;

    const auto automatic = tt::runTwinrender(run + " --out " + (dir / "a").string(), onGithub);
    EXPECT_EQ(automatic.exitCode, 2) << automatic.output;
    EXPECT_NE(automatic.output.find("\n::error file=scenes/planet.toml,title=twinrender planet%3A "
                                    "beauty.flip failed::beauty.flip = "),
              std::string::npos)
        << automatic.output;
    EXPECT_NE(automatic.output.find(" is above its max 0.0001 (" + bounds.string() + ":1:25)\n"),
              std::string::npos)
        << automatic.output;
    EXPECT_NE(automatic.output.find("\n::warning file=scenes/planet.toml,title=twinrender "
                                    "planet%3A beauty.ssim warned::beauty.ssim = "),
              std::string::npos)
        << automatic.output;
    EXPECT_EQ(count(automatic.output, "\n::"), 2u) << automatic.output;

    const auto off =
        tt::runTwinrender(run + " --annotations none --out " + (dir / "b").string(), onGithub);
    EXPECT_EQ(off.exitCode, 2) << off.output;
    EXPECT_EQ(count(off.output, "::"), 0u) << off.output;

    // Elsewhere only when asked; a shard's, and its merge's.
    const auto shard =
        tt::runTwinrender(run + " --shard 1/1 --annotations github --out " + (dir / "s1").string(),
                          "GITHUB_ACTIONS=false");
    EXPECT_EQ(count(shard.output, "\n::error file="), 1u) << shard.output;
    const std::string merge = "merge " + (dir / "s1").string() + " --out ";
    const auto quiet = tt::runTwinrender(merge + (dir / "m1").string(), "GITHUB_ACTIONS=false");
    EXPECT_EQ(quiet.exitCode, 2) << quiet.output;
    EXPECT_EQ(count(quiet.output, "::"), 0u) << quiet.output;
    const auto merged = tt::runTwinrender(merge + (dir / "m2").string(), onGithub);
    EXPECT_EQ(count(merged.output, "\n::error file=scenes/planet.toml,"), 1u) << merged.output;
    EXPECT_EQ(count(merged.output, "\n::warning file=scenes/planet.toml,"), 1u) << merged.output;

    const auto bad = tt::runTwinrender(run + " --annotations gitlab --out " + (dir / "c").string());
    EXPECT_EQ(bad.exitCode, 4) << bad.output;
    EXPECT_FALSE(fs::exists(dir / "c"));
}

}  // namespace twinrender::e2e::annotations_test
