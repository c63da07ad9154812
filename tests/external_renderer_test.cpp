// The external renderer protocol (app/external_renderer.h, docs/external.md) end to end: an
// analytic renderer of one particle's sphere (tests/adapters/analytic_sphere.py, numpy) run
// through it measures as the reference to float precision, so the export and the conventions
// (matrices, pixel centres, eye depth, coverage, normals) are exact; and each way a renderer
// can misbehave is a clear error naming the renderer and the frame, exit 4, nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/analytic_sphere.h"
#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::external_renderer_test {

namespace tt = twinrender::test;
namespace fs = std::filesystem;
using tt::ADAPTER;
using tt::SPHERE;
using tt::SPHERE_ORBIT;

namespace {

tt::CommandResult external(const fs::path& out, const std::string& command,
                           const std::string& environment = "", const std::string& more = "") {
    return tt::runTwinrender("render " + SPHERE + " --renderer external --external-command '" +
                                 command + "' --out " + out.string() + more,
                             environment);
}

}  // namespace

TEST(ExternalRenderer, AnAnalyticSphereMeasuresAsTheReferenceToFloatPrecision) {
    const fs::path dir = tt::freshDir("external_sphere");
    ASSERT_EQ(tt::runTwinrender("render " + SPHERE + " --renderer raymarch --out " + dir.string())
                  .exitCode,
              0);
    const auto r = external(dir, ADAPTER);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // The request and the frame's own folder, as docs/external.md describes them.
    const nlohmann::json request =
        tt::readJson(dir / "one_sphere" / "external" / "0000" / "request.json");
    EXPECT_EQ(request["format"], "twinrender-request");
    EXPECT_EQ(request["version"], 1);
    EXPECT_EQ(request["output"]["image"], "out/image.exr");
    const nlohmann::json frame = tt::readJson(dir / "one_sphere" / "external.json");
    EXPECT_EQ(frame["timings_ms"]["total"], 0.5);  // from the renderer's out/timings.json

    const auto c = tt::runTwinrender("compare " + (dir / "one_sphere" / "raymarch.exr").string() +
                                     " " + (dir / "one_sphere" / "external.exr").string() +
                                     " --scene " + SPHERE + " --out " + (dir / "c").string());
    ASSERT_EQ(c.exitCode, 0) << c.output;
    const nlohmann::json m = tt::readJson(dir / "c" / "metrics.json")["metrics"];
    // Every pixel centre on the same side of the silhouette: the reference samples the pixel
    // centres (spp 1) as the adapter's rays do.
    EXPECT_EQ(m["coverage.iou"], 1.0);
    EXPECT_EQ(m["silhouette.mean_px"], 0.0);
    // The reference refines its root to 1e-4 h: at an eye depth of about 4 h, 2.5e-5 of it.
    EXPECT_LT(m["depth.rel_mean"].get<double>(), 2.5e-5);
    // Normals of the same sphere at points 1e-4 h apart: far under a thousandth of a degree.
    EXPECT_LT(m["normal.mean_deg"].get<double>(), 1e-3);
}

TEST(ExternalRenderer, EachMisbehaviourIsAClearErrorNamingTheRendererAndFrame) {
    const fs::path dir = tt::freshDir("external_bad");
    struct Case {
        const char* name;
        std::string command, environment, more, says;
    };
    const Case cases[] = {
        {"missing", "/no/such/renderer", "", "", "not found or is not executable"},
        {"exit", "echo the GPU caught fire >&2; exit 3", "", "",
         "exited with 3; the last lines of its standard error:\n    the GPU caught fire"},
        {"timeout", "sleep 30; true", "", " --external-timeout 0.5",
         "passed its time limit of 0.5 s; its process group was ended"},
        {"no_image", "true", "", "", "wrote no image"},
        {"nan", ADAPTER, "ANALYTIC_SPHERE_FAULT=nan", "", "nan at pixel (0, 0) of channel R"},
        {"size", ADAPTER, "ANALYTIC_SPHERE_FAULT=size", "", "its image is 65x48 pixels"},
    };
    for (const Case& k : cases) {
        const fs::path out = dir / k.name;
        const auto start = std::chrono::steady_clock::now();
        const auto r = external(out, k.command, k.environment, k.more);
        EXPECT_EQ(r.exitCode, 4) << k.name << "\n" << r.output;
        EXPECT_NE(r.output.find("external renderer '"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("frame 0 of one_sphere"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(k.says), std::string::npos) << k.name << "\n" << r.output;
        EXPECT_FALSE(fs::exists(out / "one_sphere" / "external.exr")) << k.name;
        EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                  20.0)
            << k.name;
    }
}

TEST(ExternalRenderer, ADepthInAnotherConventionIsNotComparable) {
    const fs::path dir = tt::freshDir("external_depth");
    ASSERT_EQ(tt::runTwinrender("render " + SPHERE + " --renderer raymarch --out " + dir.string())
                  .exitCode,
              0);
    ASSERT_EQ(external(dir, ADAPTER, "ANALYTIC_SPHERE_FAULT=depth").exitCode, 0);
    const auto c = tt::runTwinrender("compare " + (dir / "one_sphere" / "raymarch.exr").string() +
                                     " " + (dir / "one_sphere" / "external.exr").string() +
                                     " --out " + (dir / "c").string());
    EXPECT_EQ(c.exitCode, 3) << c.output;
    EXPECT_NE(c.output.find("must be the eye depth along the view axis"), std::string::npos)
        << c.output;
}

// `run --test external`: the renderer of one's own beside the reference in the report, its
// metrics held to the thresholds it provides, the others not checked.
TEST(ExternalRenderer, RunPutsItBesideTheReferenceWithTheMetricsItProvides) {
    const fs::path dir = tt::freshDir("external_run");
    tt::writeFile(dir / "bounds.toml",
                  "\"coverage.iou\" = { min = 0.999 }\n\"shadow.iou\" = { min = 0.99 }\n");
    const auto r = tt::runTwinrender("run " + SPHERE + " --test external --external-command '" +
                                     ADAPTER + "' --thresholds " + (dir / "bounds.toml").string() +
                                     " --out " + (dir / "out").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json m = tt::readJson(dir / "out" / "one_sphere" / "metrics.json");
    EXPECT_EQ(m["metrics"]["coverage.iou"], 1.0);
    EXPECT_FALSE(m["metrics"].contains("shadow.iou"));
    const auto& notProvided = m["not_provided"];
    EXPECT_NE(std::find(notProvided.begin(), notProvided.end(), "shadow.iou"), notProvided.end());
    ASSERT_EQ(m["checks"].size(), 1u) << m["checks"];
    EXPECT_EQ(m["checks"][0]["metric"], "coverage.iou");
    EXPECT_TRUE(fs::exists(dir / "out" / "one_sphere" / "external.exr"));
    const std::string page = tt::readText(dir / "out" / "one_sphere" / "index.html");
    EXPECT_NE(page.find("external: /usr/bin/python3"), std::string::npos);
    // Its images in the panel and the swap view where the built-in renderer's would be.
    EXPECT_NE(page.find("src=\"external.beauty.png\""), std::string::npos);
    EXPECT_EQ(page.find("wrote no beauty buffer"), std::string::npos);
    EXPECT_NE(page.find("shadow.iou</td><td class=\"num muted\">not provided</td>"),
              std::string::npos);
}

// A sequence through the protocol: a request and an image per frame, each frame measured, and
// the flicker of each consecutive pair against the truth's, as for the built-in renderer. The
// same frames given later as images (`run --test-images`) measure alike.
TEST(ExternalRenderer, RunMeasuresASequenceFrameByFrameWithItsFlicker) {
    const fs::path dir = tt::freshDir("external_sequence");
    const std::string orbit = SPHERE_ORBIT;
    const std::string cache = " --cache " + (dir / "cache").string();
    const auto r =
        tt::runTwinrender("run " + orbit + cache + " --test external --external-command '" +
                          ADAPTER + "' --out " + (dir / "out").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const fs::path scene = dir / "out" / "one_sphere_orbit";
    for (int frame = 0; frame < 3; ++frame) {
        const std::string folder = "000" + std::to_string(frame);
        EXPECT_EQ(tt::readJson(scene / "external" / folder / "request.json")["frame"], frame);
        EXPECT_TRUE(fs::exists(scene / "frames" / folder / "external.exr")) << folder;
    }
    EXPECT_TRUE(fs::exists(scene / "sequence.webm"));
    const nlohmann::json report = tt::readJson(scene / "metrics.json");
    const auto& frames = report["sequence"]["frames"];
    ASSERT_EQ(frames.size(), 3u) << report;
    EXPECT_FALSE(frames[0]["metrics"].contains("temporal.flicker"));
    for (int k = 0; k < 3; ++k) {
        const auto& m = frames[k]["metrics"];
        EXPECT_EQ(m["coverage.iou"], 1.0) << k;
        EXPECT_EQ(m["time.external_ms"], 0.5) << k;  // from the renderer's out/timings.json
        if (k == 0) continue;
        EXPECT_NEAR(m["temporal.flicker"].get<double>(),
                    m["temporal.frame_flip"].get<double>() -
                        m["temporal.reference_frame_flip"].get<double>(),
                    1e-12);
        // The exact sphere's normals turn with the camera as the truth's do.
        EXPECT_LT(std::abs(m["temporal.normal_flicker_deg"].get<double>()), 1e-3) << k;
    }
    EXPECT_TRUE(report["metrics"]["temporal.flicker_mean"].is_number());

    // The frames as images rendered earlier, DIR/<scene>/<frame>.exr, without their times.
    const fs::path images = dir / "images" / "one_sphere_orbit";
    fs::create_directories(images);
    for (const char* f : {"0000", "0001", "0002"})
        fs::copy_file(scene / "frames" / f / "external.exr", images / (std::string(f) + ".exr"));
    const auto later =
        tt::runTwinrender("run " + orbit + cache + " --test-images " + (dir / "images").string() +
                          " --out " + (dir / "later").string());
    ASSERT_EQ(later.exitCode, 0) << later.output;
    const nlohmann::json again = tt::readJson(dir / "later" / "one_sphere_orbit" / "metrics.json");
    for (int k = 0; k < 3; ++k) {
        for (const auto& [key, value] : frames[k]["metrics"].items()) {
            if (key != "time.external_ms" && key != "time.raymarch_ms") {
                EXPECT_EQ(again["sequence"]["frames"][k]["metrics"][key], value) << k << " " << key;
            }
        }
    }
    EXPECT_FALSE(again["metrics"].contains("time.external_ms"));
}

// Every metric of `a` that both paths make (not the times, nor the error split the built-in path
// alone makes) is in `b` with the same value; the temporal ones, which measure the frames'
// display images (the built-in renderer's tonemapped on the GPU, an external frame's on the CPU),
// within float rounding. Returns how many were compared.
int expectSameMetrics(const nlohmann::json& a, const nlohmann::json& b, const std::string& where) {
    int compared = 0;
    for (const auto& [key, value] : a.items()) {
        if (key.rfind("time.", 0) == 0 || key.find("surface.") == 0 || key.find("lighting.") == 0 ||
            key.find("shading.") == 0)
            continue;
        EXPECT_TRUE(b.contains(key)) << where << " " << key;
        if (key.rfind("temporal.", 0) == 0) {
            EXPECT_NEAR(value.get<double>(), b[key].get<double>(), 1e-6) << where << " " << key;
        } else {
            EXPECT_EQ(value, b[key]) << where << " " << key;
        }
        ++compared;
    }
    return compared;
}

// The protocol's own end to end: twinrender's real-time renderer run through it by a small
// adapter (tests/adapters/builtin_realtime.py) measures as the built-in path on the same scenes,
// a still one and a sequence (a churning ball, three frames: a request each, and the flicker).
// The renderer is deterministic, so every image metric is the same number. Bloom is off in the
// sequence: it is in the built-in renderer's display image only, which the flicker measures.
TEST(ExternalRenderer, TheBuiltInRendererThroughTheProtocolMeasuresAsTheBuiltInPath) {
    const fs::path dir = tt::freshDir("external_builtin");
    const std::string planet = ::twinrender::testing::sourceDir().string() + "/scenes/planet.toml";
    tt::writeFile(dir / "churn.toml",
                  "name = \"churn\"\n[camera]\nposition = [0.0, -4.0, 1.0]\n"
                  "[light]\ndirection = [-1.0, 0.6, -0.4]\n[realtime]\nbloom.enabled = false\n"
                  "[[bodies]]\nname = \"ball\"\nshape = \"ball\"\nradius = 1.0\n"
                  "particles = 1500\nchurn = 0.3\n[sequence]\nfirst = 0\nlast = 2\nfps = 4.0\n");
    const std::string scenes = planet + " " + (dir / "churn.toml").string();
    const std::string common = " --set camera.width=96 --set camera.height=72 --cache " +
                               (dir / "cache").string() + " --thresholds " +
                               (dir / "none.toml").string();
    tt::writeFile(dir / "none.toml", "# no bounds\n");
    const auto builtIn =
        tt::runTwinrender("run " + scenes + common + " --out " + (dir / "builtin").string());
    ASSERT_EQ(builtIn.exitCode, 0) << builtIn.output;
    const std::string adapter = "/usr/bin/python3 " + ::twinrender::testing::sourceDir().string() +
                                "/tests/adapters/builtin_realtime.py " +
                                ::twinrender::testing::twinrenderProgram();
    const auto external =
        tt::runTwinrender("run " + scenes + common + " --test external --external-command '" +
                          adapter + "' --out " + (dir / "external").string());
    ASSERT_EQ(external.exitCode, 0) << external.output;
    const nlohmann::json a = tt::readJson(dir / "builtin" / "planet" / "metrics.json")["metrics"];
    const nlohmann::json b = tt::readJson(dir / "external" / "planet" / "metrics.json")["metrics"];
    EXPECT_GT(expectSameMetrics(a, b, "planet"), 20);
    const nlohmann::json c = tt::readJson(dir / "builtin" / "churn" / "metrics.json");
    const nlohmann::json d = tt::readJson(dir / "external" / "churn" / "metrics.json");
    expectSameMetrics(c["metrics"], d["metrics"], "churn");
    ASSERT_EQ(c["sequence"]["frames"].size(), 3u);
    ASSERT_EQ(d["sequence"]["frames"].size(), 3u);
    for (int k = 0; k < 3; ++k)
        EXPECT_GT(expectSameMetrics(c["sequence"]["frames"][k]["metrics"],
                                    d["sequence"]["frames"][k]["metrics"],
                                    "churn frame " + std::to_string(k)),
                  20);
    EXPECT_GT(d["metrics"]["temporal.flicker_mean"].get<double>(), 0.001);  // churn flickers
}

}  // namespace twinrender::e2e::external_renderer_test
