// `run --test-images DIR` (app/test_images.h, docs/external.md): images a user rendered earlier,
// one per scene and frame, are judged as the external renderer's own output is, with the same
// metrics, thresholds and reports; a missing or unsound image is bad input naming the scene, the
// frame and the file, before anything renders, and nothing is written.
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/analytic_sphere.h"
#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::test_images_test {

namespace tt = twinrender::test;
namespace fs = std::filesystem;
using tt::ADAPTER;
using tt::SPHERE;
using tt::SPHERE_ORBIT;

TEST(TestImages, RunJudgesImagesRenderedEarlierAsTheExternalRendererItself) {
    const fs::path dir = tt::freshDir("test_images_run");
    tt::writeFile(dir / "bounds.toml",
                  "\"coverage.iou\" = { min = 0.999 }\n\"shadow.iou\" = { min = 0.99 }\n");
    const std::string common =
        " --cache " + (dir / "cache").string() + " --thresholds " + (dir / "bounds.toml").string();
    const auto external =
        tt::runTwinrender("run " + SPHERE + common + " --test external --external-command '" +
                          ADAPTER + "' --out " + (dir / "external").string());
    ASSERT_EQ(external.exitCode, 0) << external.output;
    // The renderer's image, and its times beside it.
    fs::create_directories(dir / "images" / "one_sphere");
    fs::copy_file(dir / "external" / "one_sphere" / "external.exr",
                  dir / "images" / "one_sphere" / "0000.exr");
    tt::writeFile(dir / "images" / "one_sphere" / "0000.timings.json", "{\"total\": 2.5}");
    const auto r = tt::runTwinrender(
        "run " + SPHERE + common + " --test-images " + (dir / "images").string() + " --junit " +
        (dir / "junit.xml").string() + " --out " + (dir / "out").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json a = tt::readJson(dir / "external" / "one_sphere" / "metrics.json");
    const nlohmann::json b = tt::readJson(dir / "out" / "one_sphere" / "metrics.json");
    for (const auto& [key, value] : a["metrics"].items()) {
        if (key.rfind("time.", 0) != 0) {
            EXPECT_EQ(b["metrics"][key], value) << key;
        }
    }
    EXPECT_EQ(b["metrics"]["time.external_ms"], 2.5);
    EXPECT_EQ(b["not_provided"], a["not_provided"]);
    // Held to the bounds of the metrics it provides only, as the external renderer was.
    ASSERT_EQ(b["checks"].size(), 1u) << b["checks"];
    EXPECT_EQ(b["checks"][0]["metric"], "coverage.iou");
    EXPECT_NE(tt::readText(dir / "junit.xml").find("one_sphere"), std::string::npos);
    const std::string page = tt::readText(dir / "out" / "one_sphere" / "index.html");
    EXPECT_NE(page.find("images: " + (dir / "images").string()), std::string::npos);
    EXPECT_NE(page.find("src=\"external.beauty.png\""), std::string::npos);
}

TEST(TestImages, AMissingOrUnsoundImageIsBadInputNamingTheSceneFrameAndFile) {
    const fs::path dir = tt::freshDir("test_images_bad");
    // A sound image to spoil: the reference's own, which has every channel.
    ASSERT_EQ(tt::runTwinrender("render " + SPHERE + " --renderer raymarch --out " +
                                (dir / "ref").string() + " --set camera.width=32")
                  .exitCode,
              0);
    const std::string writeNan =
        "/usr/bin/python3 -c 'import sys; sys.path.insert(0, \"" +
        ::twinrender::testing::sourceDir().string() +
        "/examples/external\"); import numpy as np; from pathlib import Path; "
        "from twinrender_external import write_exr; "
        "r = np.zeros((48, 64)); r[3, 5] = np.nan; write_exr(Path(sys.argv[1]), "
        "{\"R\": r, \"G\": r, \"B\": r})' ";
    struct Case {
        const char* name;
        std::string make;  // a shell command given the image's path; empty: no image
        std::string says;
    };
    const Case cases[] = {
        {"missing", "", "no image at "},
        {"size", "cp " + (dir / "ref" / "one_sphere" / "raymarch.exr").string(),
         "its image is 32x48 pixels; the camera's is 64x48"},
        {"nan", writeNan, "nan at pixel (5, 3) of channel R"},
        {"not_an_image", "echo not an image >", "cannot read the image"},
    };
    for (const Case& k : cases) {
        const fs::path images = dir / k.name / "images";
        const fs::path file = images / "one_sphere" / "0000.exr";
        fs::create_directories(file.parent_path());
        if (!k.make.empty()) {
            ASSERT_EQ(std::system((k.make + " " + file.string()).c_str()), 0);
        }
        const fs::path out = dir / k.name / "out";
        const auto r = tt::runTwinrender("run " + SPHERE + " --test-images " + images.string() +
                                         " --out " + out.string());
        EXPECT_EQ(r.exitCode, 4) << k.name << "\n" << r.output;
        EXPECT_NE(r.output.find("scene one_sphere"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("frame 0"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(file.string()), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(k.says), std::string::npos) << k.name << "\n" << r.output;
        EXPECT_FALSE(fs::exists(out)) << k.name;
    }
    // A depth in another convention is caught against the reference, as the protocol's is: the
    // scene fails, saying what Z must be.
    const fs::path depth = dir / "depth";
    ASSERT_EQ(tt::runTwinrender("render " + SPHERE + " --renderer external --external-command '" +
                                    ADAPTER + "' --out " + depth.string(),
                                "ANALYTIC_SPHERE_FAULT=depth")
                  .exitCode,
              0);
    fs::create_directories(depth / "images" / "one_sphere");
    fs::copy_file(depth / "one_sphere" / "external.exr",
                  depth / "images" / "one_sphere" / "0000.exr");
    const auto d =
        tt::runTwinrender("run " + SPHERE + " --test-images " + (depth / "images").string() +
                          " --out " + (depth / "out").string());
    EXPECT_EQ(d.exitCode, 2) << d.output;
    EXPECT_NE(d.output.find("must be the eye depth along the view axis"), std::string::npos)
        << d.output;

    // A frame of a sequence missing: named with its path, before any frame renders.
    const fs::path images = dir / "sequence" / "images";
    fs::create_directories(images / "one_sphere_orbit");
    for (const char* f : {"0000", "0001"})
        fs::copy_file(dir / "ref" / "one_sphere" / "raymarch.exr",
                      images / "one_sphere_orbit" / (std::string(f) + ".exr"));
    const auto r =
        tt::runTwinrender("run " + SPHERE_ORBIT + " --set camera.width=32 --test-images " +
                          images.string() + " --out " + (dir / "sequence" / "out").string());
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("scene one_sphere_orbit"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("frame 2: no image at " +
                            (images / "one_sphere_orbit" / "0002.exr").string()),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir / "sequence" / "out"));
}

}  // namespace twinrender::e2e::test_images_test
