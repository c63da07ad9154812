// VTK's screen-space fluid renderer (examples/vtk_fluid/render.py) as the first real client of
// the external renderer protocol, under Xvfb: on one particle's sphere, with the mapper's
// radius at the sphere's (0.851 h at surface level 0.05: w(0.851) = 0.05 pi / (0.1 (4/3) pi)),
// its coverage is the reference's and, unfiltered, its normals are the sphere's within what 8
// bits of colour per component allow; its filtered normals are what VTK's filter makes of them.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::vtk_fluid_test {

namespace tt = twinrender::test;
namespace fs = std::filesystem;

namespace {

const std::string SPHERE =
    ::twinrender::testing::sourceDir().string() + "/tests/scenes/one_sphere.toml";
const std::string SIZE = " --set camera.width=160 --set camera.height=120";

// One X server (Xvfb) for the test's VTK windows: xvfb-run -a per frame races with the server
// it just ended (VTK then finds a "bad X server connection").
class VirtualDisplay {
  public:
    VirtualDisplay() : mNumber(200 + static_cast<int>(getpid() % 500)) {
        // A number no server holds (its lock file absent).
        while (fs::exists("/tmp/.X" + std::to_string(mNumber) + "-lock")) ++mNumber;
        const fs::path socket = fs::path("/tmp/.X11-unix") / ("X" + std::to_string(mNumber));
        const std::string start = "Xvfb :" + std::to_string(mNumber) +
                                  " -screen 0 1280x1024x24 -nolisten tcp > /dev/null 2>&1 & "
                                  "echo $!";
        FILE* pipe = popen(start.c_str(), "r");
        if (pipe && std::fscanf(pipe, "%d", &mPid) != 1) mPid = 0;
        if (pipe) pclose(pipe);
        for (int k = 0; k < 200 && !fs::exists(socket); ++k)
            std::this_thread::sleep_for(std::chrono::milliseconds(25));
        std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the socket, then the server
    }
    ~VirtualDisplay() {
        if (mPid > 0) kill(mPid, SIGTERM);
    }
    VirtualDisplay(const VirtualDisplay&) = delete;
    VirtualDisplay& operator=(const VirtualDisplay&) = delete;
    std::string environment() const { return "DISPLAY=:" + std::to_string(mNumber); }

  private:
    int mNumber = 0;
    int mPid = 0;
};

nlohmann::json vtkMetrics(const fs::path& dir, const std::string& filter,
                          const VirtualDisplay& display) {
    const std::string command = "/usr/bin/python3 " + ::twinrender::testing::sourceDir().string() +
                                "/examples/vtk_fluid/render.py --radius-scale 0.851 --filter " +
                                filter;
    const fs::path out = dir / filter;
    const std::string render = "render " + SPHERE + " --renderer external --external-command '" +
                               command + "' --out " + out.string() + SIZE;
    auto r = tt::runTwinrender(render, display.environment());
    // A loaded machine's X server may refuse VTK's first connection: once more.
    if (r.exitCode != 0 && r.output.find("bad X server connection") != std::string::npos)
        r = tt::runTwinrender(render, display.environment());
    EXPECT_EQ(r.exitCode, 0) << r.output;
    const auto c = tt::runTwinrender("compare " + (dir / "one_sphere" / "raymarch.exr").string() +
                                     " " + (out / "one_sphere" / "external.exr").string() +
                                     " --out " + (out / "c").string());
    EXPECT_EQ(c.exitCode, 0) << c.output;
    return tt::readJson(out / "c" / "metrics.json");
}

}  // namespace

TEST(VtkFluid, TheAdapterMeetsTheProtocolsConventions) {
    const fs::path dir = tt::freshDir("vtk_fluid");
    ASSERT_EQ(
        tt::runTwinrender("render " + SPHERE + " --renderer raymarch --out " + dir.string() + SIZE)
            .exitCode,
        0);
    const VirtualDisplay display;
    const nlohmann::json none = vtkMetrics(dir, "none", display);
    // Same sphere, same pixel centres: all but a rim pixel or two agree (measured 0.998).
    EXPECT_GT(none["metrics"]["coverage.iou"].get<double>(), 0.99);
    EXPECT_LT(none["metrics"]["silhouette.mean_px"].get<double>(), 0.2);
    // Normals read back from 8-bit colours, each component to 1/255, and VTK's own normals
    // from its depth (measured 0.89 degrees).
    EXPECT_LT(none["metrics"]["normal.mean_deg"].get<double>(), 1.5);
    // Depth is not provided: VTK leaves 0 in the depth buffer where it draws the fluid.
    const auto& notProvided = none["not_provided"];
    EXPECT_NE(std::find(notProvided.begin(), notProvided.end(), "depth.rel_mean"),
              notProvided.end());
    // The filtered surface of one particle is not its sphere: VTK's narrow-range filter
    // flattens it (measured 16 degrees), the coverage stays.
    const nlohmann::json filtered = vtkMetrics(dir, "narrow_range", display);
    EXPECT_GT(filtered["metrics"]["coverage.iou"].get<double>(), 0.99);
    EXPECT_GT(filtered["metrics"]["normal.mean_deg"].get<double>(),
              none["metrics"]["normal.mean_deg"].get<double>());
}

}  // namespace twinrender::e2e::vtk_fluid_test
