// Bad input is rejected before any work starts: exit code 4, a message that names the file,
// line or key, and no output file.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "core/particle_file.h"
#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::bad_input_test {

namespace tt = twinrender::test;

namespace {

// A small valid scene; each test breaks one thing in it.
std::string sceneText(const std::string& cameraExtra = "", const std::string& bodyExtra = "",
                      const std::string& materialExtra = "", const std::string& body = "") {
    return "name = \"probe\"\n"
           "[camera]\n"
           "position = [0.0, -4.0, 0.0]\n"
           "width = 32\n"
           "height = 24\n" +
           cameraExtra +
           "\n[[materials]]\n"
           "name = \"rock\"\n"
           "diffuse = [0.5, 0.5, 0.5]\n" +
           materialExtra + "\n[[bodies]]\n" +
           (body.empty() ? "name = \"ball\"\nshape = \"ball\"\nradius = 1.0\nparticles = "
                           "500\nmaterial = \"rock\"\n"
                         : body) +
           bodyExtra;
}

struct Rejected {
    std::string output;
    std::size_t filesWritten;
};

Rejected renderBroken(const std::string& name, const std::string& scene,
                      const std::string& extraArgs = "") {
    const auto dir = tt::freshDir(name);
    tt::writeFile(dir / "scene.toml", scene);
    const auto out = dir / "out";
    const auto r =
        tt::runTwinrender("render " + (dir / "scene.toml").string() +
                          " --renderer raymarch --out " + out.string() + " " + extraArgs);
    EXPECT_EQ(r.exitCode, 4) << r.output;
    return {r.output, tt::countFiles(out)};
}

const std::filesystem::path BALL_SSF =
    ::twinrender::testing::sourceDir() / "data" / "opensph_ball" / "ball.ssf";

// The OpenSPH ball's bytes (empty when it is missing).
std::string readBall() {
    std::ifstream in(BALL_SSF, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

struct FileRender {
    std::filesystem::path dir;
    tt::CommandResult result;
};

// Renders the probe scene with one body read from `file`, written beside it with `bytes`.
FileRender renderFileBody(const std::string& name, const std::string& file,
                          const std::string& bytes) {
    const auto dir = tt::freshDir(name);
    std::ofstream(dir / file, std::ios::binary)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    tt::writeFile(dir / "scene.toml", sceneText("", "", "",
                                                "name = \"cloud\"\nshape = \"file\"\npath = \"" +
                                                    file + "\"\nmaterial = \"rock\"\n"));
    return {dir, tt::runTwinrender("render " + (dir / "scene.toml").string() +
                                   " --renderer raymarch --out " + (dir / "out").string())};
}

// Exit 4, a message holding `part`, nothing written.
void expectRejected(const FileRender& f, const std::string& part) {
    EXPECT_EQ(f.result.exitCode, 4) << f.result.output;
    EXPECT_NE(f.result.output.find(part), std::string::npos) << f.result.output;
    EXPECT_EQ(tt::countFiles(f.dir / "out"), 0u);
}

}  // namespace

TEST(BadInput, UnknownKeyNamesFileLineAndKey) {
    const auto r = renderBroken("unknown_key", sceneText("widht = 40\n"));
    EXPECT_NE(r.output.find("scene.toml:6:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("camera.widht"), std::string::npos) << r.output;
    EXPECT_EQ(r.filesWritten, 0u);
}

TEST(BadInput, WrongTypeNamesTheKey) {
    const auto r = renderBroken("wrong_type", sceneText("fov_y_deg = \"wide\"\n"));
    EXPECT_NE(r.output.find("camera.fov_y_deg"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("wrong type"), std::string::npos) << r.output;
    EXPECT_EQ(r.filesWritten, 0u);
}

TEST(BadInput, UnknownMaterialIsNamed) {
    const auto r = renderBroken(
        "unknown_material",
        sceneText("", "", "",
                  "name = \"ball\"\nshape = \"ball\"\nparticles = 500\nmaterial = \"mud\"\n"));
    EXPECT_NE(r.output.find("'mud'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("rock"), std::string::npos) << r.output;  // lists what exists
    EXPECT_EQ(r.filesWritten, 0u);
}

TEST(BadInput, NanAndNegativeSmoothingLengthInAFileNameTheLine) {
    for (const std::string bad : {"nan", "-0.1"})
        expectRejected(
            renderFileBody("bad_h", "particles.csv", "x,y,z,h\n0,0,0,0.1\n0.1,0,0," + bad + "\n"),
            "particles.csv:3");
}

TEST(BadInput, TruncatedSsfNamesTheFile) {
    const std::string ball = readBall();
    ASSERT_FALSE(ball.empty()) << "data/opensph_ball/ball.ssf is missing";
    expectRejected(renderFileBody("truncated_ssf", "cut.ssf", ball.substr(0, 200000)),
                   "cut.ssf: truncated");
}

// A position a double holds but a float (the renderers' particles) does not: once the kind of
// value that kept the neighbour grids of the derived attributes busy for minutes.
TEST(BadInput, PositionBeyondTheFloatRangeNamesTheParticle) {
    expectRejected(
        renderFileBody("beyond_float", "particles.csv", "x,y,z,h\n0,0,0,0.1\n1e300,0,0,0.1\n"),
        "particles.csv: particle 1: position (1e+300, 0, 0)");
}

// The OpenSPH ball with one smoothing length's bytes flipped into 1e-300 (a valid double, a
// float 0): rejected naming the file, the particle and the value, before any work.
TEST(BadInput, SsfWithAFlippedSmoothingLengthNamesTheParticle) {
    std::string bytes = readBall();
    ASSERT_FALSE(bytes.empty()) << "data/opensph_ball/ball.ssf is missing";
    // Particle 0's (x, y, z, h): found by the values the reader gives.
    const auto ball = twinrender::core::readParticleFile(BALL_SSF);
    const double first[4] = {ball.position[0].x, ball.position[0].y, ball.position[0].z, ball.h[0]};
    const auto at = bytes.find(std::string(reinterpret_cast<const char*>(first), sizeof first));
    ASSERT_NE(at, std::string::npos);
    const double flipped = 1e-300;
    bytes.replace(at + 24, 8, reinterpret_cast<const char*>(&flipped), 8);
    expectRejected(renderFileBody("flipped_ssf", "flipped.ssf", bytes),
                   "flipped.ssf: particle 0: smoothing length h = 1e-300");
}

// One particle 1e30 away from a body of small ones: a valid, if odd, file that renders (the
// neighbour grids give the stray particle a cluster of its own; ctest's timeout catches a
// hang).
TEST(BadInput, ParticleFarFromTheRestStillRenders) {
    std::string csv = "x,y,z,h\n";
    for (int i = 0; i < 1000; ++i)
        csv += fmt::format("{},{},{},0.15\n", (i % 10) * 0.1 - 0.45, (i / 10 % 10) * 0.1 - 0.45,
                           (i / 100) * 0.1 - 0.45);
    csv += "1e30,-1e30,1e30,0.15\n";
    const FileRender f = renderFileBody("far_particle", "particles.csv", csv);
    EXPECT_EQ(f.result.exitCode, 0) << f.result.output;
    EXPECT_TRUE(std::filesystem::exists(f.dir / "out" / "probe" / "raymarch.exr"));
}

TEST(BadInput, MissingTextureNamesTheFileAndKey) {
    const auto r = renderBroken("missing_texture", sceneText("", "", "specular = \"shiny.png\"\n"));
    EXPECT_NE(r.output.find("shiny.png"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("materials[0].specular"), std::string::npos) << r.output;
    EXPECT_EQ(r.filesWritten, 0u);
}

TEST(BadInput, UnknownProceduralIsNamed) {
    const auto r =
        renderBroken("unknown_procedural", sceneText("", "", "emission = \"procedural:plasma\"\n"));
    EXPECT_NE(r.output.find("plasma"), std::string::npos) << r.output;
    EXPECT_EQ(r.filesWritten, 0u);
}

TEST(BadInput, TomlSyntaxErrorNamesTheLine) {
    const auto r = renderBroken("syntax", "name = \"x\"\n[camera\nwidth = 3\n");
    EXPECT_NE(r.output.find("scene.toml:2"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("syntax"), std::string::npos) << r.output;
    EXPECT_EQ(r.filesWritten, 0u);
}

TEST(BadInput, AbsurdResolutionIsRejected) {
    const auto r =
        renderBroken("resolution", sceneText("", "", "", ""), "--set camera.width=1000000");
    EXPECT_NE(r.output.find("camera.width"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("out of range"), std::string::npos) << r.output;
    EXPECT_EQ(r.filesWritten, 0u);
}

TEST(BadInput, UnknownOverrideKeyIsNamed) {
    const auto r = renderBroken("unknown_set", sceneText(), "--set raymarch.surface_levle=0.2");
    EXPECT_NE(r.output.find("raymarch.surface_levle"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("--set"), std::string::npos) << r.output;
    EXPECT_EQ(r.filesWritten, 0u);
}

TEST(BadInput, OverridesOutOfRangeOrOfTheWrongTypeNameTheOverride) {
    // Every section: the message names the --set, the key as written and what is allowed.
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"bodies.ball.particles=2000000000",
         "key 'bodies.ball.particles' is out of range: 2000000000 (allowed: 1..50000000)"},
        {"bodies.0.radius=big", "key 'bodies.0.radius' has the wrong type: expected a number"},
        {"materials.rock.shininess=0",
         "key 'materials.rock.shininess' is out of range: 0 (allowed: 1..10000)"},
        {"light.ambient=-1", "key 'light.ambient' is out of range: -1 (allowed: 0..1000000000)"},
        {"camera.height=tall", "key 'camera.height' has the wrong type: expected an integer"},
        {"raymarch.spp=0", "key 'raymarch.spp' is out of range: 0 (allowed: 1..16384)"},
        {"raymarch.shadows=7", "key 'raymarch.shadows' has the wrong type: expected true or false"},
        {"realtime.depth=linear",
         "key 'realtime.depth' is out of range: \"linear\" (allowed: log | standard | reversed)"},
        {"realtime.ssss.enabled=3",
         "key 'realtime.ssss.enabled' has the wrong type: expected true or false"},
    };
    for (const auto& [assignment, error] : cases) {
        const auto r = renderBroken("override_" + assignment.substr(0, assignment.find('=')),
                                    sceneText(), "--set " + assignment);
        EXPECT_NE(r.output.find("error: --set " + assignment + ": " + error), std::string::npos)
            << r.output;
        EXPECT_EQ(r.filesWritten, 0u);
    }
    // The comparison's thresholds, read by the commands that compare.
    const auto dir = tt::freshDir("override_compare");
    tt::writeFile(dir / "scene.toml", sceneText());
    const auto r = tt::runTwinrender("run " + (dir / "scene.toml").string() + " --out " +
                                     (dir / "out").string() +
                                     " --set compare.thresholds.beauty.flip.max=high");
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("error: --set compare.thresholds.beauty.flip.max=high: key "
                            "'compare.thresholds.beauty.flip.max': the bound must be a number"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(tt::countFiles(dir / "out"), 0u);
}

TEST(BadInput, TwoSubpixelOptionsAtOnceAreNamed) {
    const auto r = renderBroken("two_subpixel_options", sceneText(),
                                "--set realtime.particles.min_pixels=1 --set "
                                "realtime.particles.halo_pixels=2");
    EXPECT_NE(r.output.find("particles.halo_pixels and particles.min_pixels"), std::string::npos)
        << r.output;
    EXPECT_EQ(r.filesWritten, 0u);
}

TEST(BadInput, MissingSceneFile) {
    const auto r = tt::runTwinrender("render /nonexistent/scene.toml --renderer raymarch");
    EXPECT_EQ(r.exitCode, 4);
    EXPECT_NE(r.output.find("/nonexistent/scene.toml"), std::string::npos) << r.output;
}

TEST(BadInput, ThresholdOnAnUnknownMetricNamesTheFileKeyAndTheMetrics) {
    const auto dir = tt::freshDir("unknown_metric");
    tt::writeFile(dir / "scene.toml", sceneText());
    tt::writeFile(dir / "bounds.toml",
                  "\"beauty.flip\" = { max = 0.2 }\n\"normal.mean_degs\" = { max = 3.0 }\n");
    const auto out = dir / "out";
    const auto r = tt::runTwinrender("run " + (dir / "scene.toml").string() + " --thresholds " +
                                     (dir / "bounds.toml").string() + " --out " + out.string());
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("bounds.toml:2:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("unknown metric 'normal.mean_degs'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("normal.mean_deg, normal.p95_deg"), std::string::npos) << r.output;
    EXPECT_EQ(tt::countFiles(out), 0u);

    // The same in the scene file's own bounds.
    tt::writeFile(dir / "own.toml",
                  sceneText() + "\n[compare.thresholds]\n\"shadow.iou_min\" = { min = 0.9 }\n");
    const auto own =
        tt::runTwinrender("run " + (dir / "own.toml").string() + " --out " + out.string());
    EXPECT_EQ(own.exitCode, 4) << own.output;
    EXPECT_NE(own.output.find("own.toml:"), std::string::npos) << own.output;
    EXPECT_NE(own.output.find("unknown metric 'shadow.iou_min'"), std::string::npos) << own.output;
    EXPECT_EQ(tt::countFiles(out), 0u);
}

// A user's surface shader that does not compile: exit 4 naming the shader's file and line,
// before anything renders (the raymarcher included), no output.
TEST(BadInput, UserShaderThatDoesNotCompileNamesItsLineAndWritesNothing) {
    const auto dir = tt::freshDir("bad_user_shader");
    tt::writeFile(dir / "scene.toml", sceneText());
    tt::writeFile(dir / "mine.glsl",
                  "void filterSurface(ivec2 pixel, inout SurfaceSample s) {\n"
                  "    s.depth = s.depht;\n"
                  "}\n");
    const auto out = dir / "out";
    const auto r = tt::runTwinrender(
        "render " + (dir / "scene.toml").string() + " --renderer both --out " + out.string() +
        " --set realtime.surface.shader=" + (dir / "mine.glsl").string());
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find((dir / "mine.glsl").string() + ":2:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("depht"), std::string::npos) << r.output;
    EXPECT_EQ(tt::countFiles(out), 0u);
}

// A shader file that cannot be read names the key and the path.
TEST(BadInput, MissingUserShaderNamesTheKeyAndThePath) {
    const auto r = renderBroken("missing_user_shader", sceneText(),
                                "--set realtime.surface.shader=nowhere/mine.glsl");
    EXPECT_NE(r.output.find("realtime.surface.shader"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("nowhere/mine.glsl"), std::string::npos) << r.output;
    EXPECT_EQ(r.filesWritten, 0u);
}

}  // namespace twinrender::e2e::bad_input_test
