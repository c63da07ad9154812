// A body's atmosphere end to end: the real-time end points (realtime.atmosphere.end_point)
// against the reference's exact hit, compared by `twinrender run` (inscatter.rmse,
// inscatter.rel) on a ball with a thin atmosphere (tests/scenes/atmosphere_ball.toml).
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::atmosphere_test {

namespace tt = twinrender::test;
namespace fs = std::filesystem;

namespace {

const fs::path SCENE =
    ::twinrender::testing::sourceDir() / "tests" / "scenes" / "atmosphere_ball.toml";

std::map<std::string, double> runWith(const fs::path& dir, const std::string& name,
                                      std::vector<std::string> sets) {
    return tt::runMetrics(SCENE, dir, name, sets);
}

std::string endPoint(const std::string& name) {
    return "realtime.atmosphere.end_point=\"" + name + "\"";
}

}  // namespace

// On a perfect sphere (one particle's level set, which the inner sphere takes as its radius) the
// analytic end point is the reference's exact hit: the same model (core/atmosphere.h) at the
// same end point, pixel for pixel.
TEST(AtmosphereRun, TheSphereEndPointIsTheReferenceOnAPerfectSphere) {
    const fs::path dir = tt::freshDir("atmosphere_perfect_sphere");
    const auto r =
        runWith(dir, "sphere",
                {"bodies.ball.particles=1", "bodies.ball.lattice=\"cubic\"",
                 "camera.position=[0,-1.2,0.1]", "camera.fov_y_deg=30", endPoint("sphere")});
    ASSERT_TRUE(r.contains("inscatter.rel"));
    std::printf("perfect sphere: inscatter.rmse %.3g rel %.3g\n", r.at("inscatter.rmse"),
                r.at("inscatter.rel"));
    // Measured 0.0021: float rounding over 24 x 24 steps, and the few rim pixels whose centre
    // grazes the sphere, where the reference's root (refined to 1e-4 h) and the analytic entry
    // can fall on either side of it.
    EXPECT_LT(r.at("inscatter.rel"), 0.005);
}

// A ball whose level set is round (h = 0.25, about 1.8 particle spacings) drawn by impostors
// whose caps are its facets: a grazing ray through the thin shell magnifies each cap's step. The
// analytic sphere's in-scatter stays near the reference's and well below the impostors'.
TEST(AtmosphereRun, TheSphereEndPointBeatsTheImpostorsOnAFacetedBall) {
    const fs::path dir = tt::freshDir("atmosphere_faceted_ball");
    std::map<std::string, std::map<std::string, double>> r;
    for (const std::string name : {"impostor", "sphere"}) {
        r[name] =
            runWith(dir, name,
                    {"bodies.ball.smoothing=0.25", "bodies.ball.particles=1500", endPoint(name)});
        ASSERT_TRUE(r[name].contains("inscatter.rmse")) << name;
        std::printf("%s: inscatter.rmse %.4g rel %.4g beauty.hdrflip %.4g\n", name.c_str(),
                    r[name].at("inscatter.rmse"), r[name].at("inscatter.rel"),
                    r[name].at("beauty.hdrflip"));
    }
    // Measured: sphere 0.0037 (rel 0.22), impostor 0.0064 (rel 0.38). The sphere's rest is the
    // level set's own departure from round and the limb's pixels.
    EXPECT_LT(r["sphere"].at("inscatter.rmse"), 0.7 * r["impostor"].at("inscatter.rmse"));
    EXPECT_LT(r["sphere"].at("inscatter.rel"), 0.25);
}

}  // namespace twinrender::e2e::atmosphere_test
