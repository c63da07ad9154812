// `twinrender doctor` on this machine's GL device (llvmpipe in CI): the device and limits,
// every program variant compiled, the self-check through both per-set paths, a verdict.
#include <gtest/gtest.h>

#include <string>

#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::doctor_test {

namespace tt = twinrender::test;

TEST(DoctorCommand, CompilesEveryVariantAndPassesTheSelfCheck) {
    const auto r =
        tt::runTwinrender(std::string("doctor --scene ") +
                              ::twinrender::testing::sourceDir().string() + "/scenes/planet.toml",
                          "TWINRENDER_GL_POISON=1");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("device: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(" 0 failed"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("particles_drawn"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("self-check: pass"), std::string::npos) << r.output;
    // The stages' own records, on fresh buffers, after a glFinish per stage and on kept ones.
    for (const char* check :
         {"grid_slots_not_a_permutation", "grid_cells_out_of_order", "grid_entries_wrong",
          "draw_list_wrong", "draw_list_wrong (glFinish)", "radii_apart (kept buffers)"})
        EXPECT_NE(r.output.find(check), std::string::npos) << check << "\n" << r.output;
    EXPECT_NE(r.output.find("per-set stages: pass"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("verdict: pass"), std::string::npos) << r.output;
}

TEST(DoctorCommand, AMissingSceneIsBadInput) {
    const auto r = tt::runTwinrender("doctor --scene no_such_scene.toml");
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("no_such_scene.toml"), std::string::npos) << r.output;
}

// --self-check forces the check on llvmpipe, where it does not run unasked
// (tests/per_set_fallback_test.cpp has it fail).
TEST(RenderCommand, SelfCheckRunsBeforeTheRender) {
    const auto dir = tt::freshDir("render_self_check");
    const auto r =
        tt::runTwinrender(std::string("render ") + ::twinrender::testing::sourceDir().string() +
                          "/scenes/planet.toml --renderer realtime --self-check --out " +
                          dir.string() + " --set camera.width=96 --set camera.height=72");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("per-set self-check on "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(planet): pass"), std::string::npos) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "planet" / "realtime.exr"));
}

}  // namespace twinrender::e2e::doctor_test
