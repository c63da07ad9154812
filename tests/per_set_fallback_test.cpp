// The per-set self-check before the first real-time frame (app/per_set_check.h): where the two
// per-set paths disagree, the real-time renderer runs its per-set work on the CPU and says so on
// the terminal, in the frame's JSON and on the report's Devices table. The disagreement is
// forced by the test hook TWINRENDER_TEST_PER_SET_FAULT=zero_positions (realtime/per_set_gpu.cpp:
// the positions cleared on the device after every upload, as an NVIDIA H200 run once showed);
// TWINRENDER_SELF_CHECK_SOFTWARE=1 lets the check run unforced on llvmpipe, as on any GPU.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::per_set_fallback_test {

namespace tt = twinrender::test;
namespace fs = std::filesystem;

namespace {

const std::string PLANET = ::twinrender::testing::sourceDir().string() + "/scenes/planet.toml";
const std::string SMALL = " --set camera.width=96 --set camera.height=72";
const std::string FAULT = "TWINRENDER_TEST_PER_SET_FAULT=zero_positions";

nlohmann::json readJson(const fs::path& file) {
    std::ifstream in(file);
    return in ? nlohmann::json::parse(in) : nlohmann::json();
}

}  // namespace

TEST(PerSetFallback, ADisagreeingSelfCheckFallsBackAndSaysSo) {
    const fs::path dir = tt::freshDir("per_set_fallback_render");
    const auto r = tt::runTwinrender(
        "render " + PLANET + " --renderer realtime --self-check" + SMALL + " --out " + dir.string(),
        FAULT);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("per-set self-check on"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("FAIL"), std::string::npos) << r.output;
    // The stages alone name where the GPU's answers part from the CPU's: the upload.
    EXPECT_NE(r.output.find("first stage apart: upload: attribute_words_apart: particle 0's "
                            "position"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("runs its per-set work on the CPU"), std::string::npos) << r.output;
    const nlohmann::json frame = readJson(dir / "planet" / "realtime.json");
    ASSERT_TRUE(frame.is_object()) << r.output;
    EXPECT_NE(frame["device"].get<std::string>().find("per-set work on the CPU"), std::string::npos)
        << frame["device"];
    EXPECT_EQ(frame["counters"]["per_set_fallback"], 1.0);
    // What ran: the CPU's per-set work, which draws the planet (the faulty GPU path draws one
    // particle, or none).
    EXPECT_EQ(frame["settings"]["realtime.per_set"], "cpu");
    EXPECT_GT(frame["counters"]["particles_drawn"].get<double>(), 1000.0);
}

TEST(PerSetFallback, TheSettingKeepsTheGpuPathAndSaysSo) {
    const fs::path dir = tt::freshDir("per_set_fallback_kept");
    const auto r =
        tt::runTwinrender("render " + PLANET + " --renderer realtime --self-check" + SMALL +
                              " --set realtime.per_set_fallback=false --out " + dir.string(),
                          FAULT);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json frame = readJson(dir / "planet" / "realtime.json");
    ASSERT_TRUE(frame.is_object()) << r.output;
    EXPECT_NE(frame["device"].get<std::string>().find("failed the self-check and is kept"),
              std::string::npos)
        << frame["device"];
    EXPECT_EQ(frame["counters"]["per_set_fallback"], 0.0);
    EXPECT_EQ(frame["settings"]["realtime.per_set"], "gpu");
    // The fault itself: every position at the origin, so the GPU path draws next to nothing.
    EXPECT_LT(frame["counters"]["particles_drawn"].get<double>(), 10.0);
}

// The report's Devices table says so; the verdict is remembered in --cache per device, driver and
// build: the first run checks and writes it, the second reads it.
TEST(PerSetFallback, TheReportSaysSoAndTheCacheRemembersTheVerdict) {
    const fs::path dir = tt::freshDir("per_set_fallback_run");
    tt::writeFile(dir / "thresholds.toml", "# no bounds: this test reads the report's devices\n");
    const std::string env = FAULT + " TWINRENDER_SELF_CHECK_SOFTWARE=1";
    const std::string run = "run " + PLANET + " --cache " + (dir / "cache").string() +
                            " --thresholds " + (dir / "thresholds.toml").string() + SMALL;
    auto r = tt::runTwinrender(run + " --out " + (dir / "first").string(), env);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("FAIL"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("remembered in"), std::string::npos) << r.output;
    EXPECT_EQ(tt::countFiles(dir / "cache" / "self_check"), 1u);
    const std::string page = tt::readText(dir / "first" / "planet" / "index.html");
    EXPECT_NE(page.find("per-set work on the CPU: the GPU per-set path failed the self-check"),
              std::string::npos);
    r = tt::runTwinrender(run + " --out " + (dir / "second").string(), env);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("FAIL (remembered in"), std::string::npos) << r.output;
    // Without the hook the software rasteriser is not checked at all.
    r = tt::runTwinrender(
        "render " + PLANET + " --renderer realtime" + SMALL + " --out " + (dir / "render").string(),
        FAULT);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("per-set self-check"), std::string::npos) << r.output;
}

TEST(DoctorCommand, NamesTheFirstPerSetStageApart) {
    const auto r = tt::runTwinrender("doctor --scene " + PLANET, FAULT);
    EXPECT_EQ(r.exitCode, 2) << r.output;
    for (const char* run : {"", " (glFinish)", " (kept buffers)"})
        EXPECT_NE(r.output.find(std::string("first stage apart") + run +
                                ": upload: attribute_words_apart: particle 0's position[0]"),
                  std::string::npos)
            << run << "\n"
            << r.output;
    EXPECT_NE(r.output.find("verdict: FAIL"), std::string::npos) << r.output;
}

}  // namespace twinrender::e2e::per_set_fallback_test
