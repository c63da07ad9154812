// Sequences in the scene model: frame patterns (numeric order, gaps, a missing frame named),
// the [sequence] table and the camera's path, and the motion of generated bodies.
#include "core/sequence.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>
#include <string>
#include <vector>

#include "core/body_motion.h"
#include "core/error.h"
#include "core/frame_pattern.h"
#include "core/particles.h"
#include "tests/scratch_dir.h"

namespace twinrender::core {
namespace {

namespace fs = std::filesystem;
using twinrender::testing::freshDir;

// A one-particle CSV frame whose particle sits at x = `x`.
void writeFrame(const fs::path& file, double x) {
    std::ofstream(file) << fmt::format("x,y,z,h\n{},0,0,0.1\n", x);
}

std::vector<std::int64_t> numbers(const std::vector<FrameFile>& files) {
    std::vector<std::int64_t> n;
    for (const FrameFile& f : files) n.push_back(f.number);
    return n;
}

// A scene of one file body at `path` and the given extra TOML.
fs::path sceneFile(const fs::path& dir, const std::string& path, const std::string& extra = "") {
    const fs::path file = dir / "scene.toml";
    std::ofstream(file) << fmt::format(
        "[camera]\nposition = [0.0, -5.0, 0.0]\nwidth = 16\nheight = 12\n"
        "[[bodies]]\nname = \"fluid\"\nshape = \"file\"\npath = \"{}\"\n{}",
        path, extra);
    return file;
}

std::string errorOf(const fs::path& scene, std::vector<std::string> sets = {}) {
    try {
        loadScene(scene, sets);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(FramePattern, AGlobOrdersFramesByNumberNotByName) {
    const fs::path dir = freshDir("frame_pattern_glob");
    for (int n : {100, 9, 10}) writeFrame(dir / fmt::format("s_{}.csv", n), n);
    writeFrame(dir / "other.csv", 0);
    const auto p = FramePattern::parse(dir / "s_*.csv", "test");
    ASSERT_TRUE(p);
    EXPECT_TRUE(p->isGlob());
    const auto files = p->list();
    EXPECT_EQ(numbers(files), (std::vector<std::int64_t>{9, 10, 100}));
    EXPECT_EQ(files[1].path.filename(), "s_10.csv");
    EXPECT_EQ(p->file(100, files).filename(), "s_100.csv");
    EXPECT_TRUE(p->file(11, files).empty());
}

TEST(FramePattern, APrintfPatternTakesOnlyTheNamesItPrints) {
    const fs::path dir = freshDir("frame_pattern_printf");
    for (const char* name : {"out_0007.csv", "out_7.csv", "out_0010.csv", "out_x.csv"})
        writeFrame(dir / name, 0);
    const auto p = FramePattern::parse(dir / "out_%04d.csv", "test");
    ASSERT_TRUE(p);
    EXPECT_FALSE(p->isGlob());
    EXPECT_EQ(numbers(p->list()), (std::vector<std::int64_t>{7, 10}));
    EXPECT_EQ(p->file(123, {}).filename(), "out_0123.csv");
    EXPECT_EQ(FramePattern::parse(dir / "f_%d.csv", "t")->file(42, {}).filename(), "f_42.csv");
    // Not patterns, and malformed ones.
    EXPECT_FALSE(FramePattern::parse(dir / "ball.ssf", "t"));
    EXPECT_FALSE(FramePattern::parse(dir / "100%%.csv", "t"));
    EXPECT_THROW(FramePattern::parse(dir / "out_%x.csv", "t"), InputError);
    EXPECT_THROW(FramePattern::parse(dir / "out_%d_%d.csv", "t"), InputError);
    EXPECT_THROW(FramePattern::parse(dir / "out_*_%d.csv", "t"), InputError);
}

TEST(FramePattern, TwoFilesOfOneNumberAreAnError) {
    const fs::path dir = freshDir("frame_pattern_twice");
    writeFrame(dir / "s_1.csv", 0);
    writeFrame(dir / "s_01.csv", 0);
    try {
        FramePattern::parse(dir / "s_*.csv", "scene.toml:9:1")->list();
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("s_01.csv"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("s_1.csv"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("both frame 1"), std::string::npos) << e.what();
    }
}

TEST(Sequence, AFileBodysFramesDefaultToEveryFileWithTheirCommonStep) {
    // OpenSPH writes every N-th step: frames 0, 10, 20 are a sequence in steps of 10.
    const fs::path dir = freshDir("sequence_gaps");
    for (int n : {0, 10, 20}) writeFrame(dir / fmt::format("out_{:04d}.csv", n), n);
    const Scene s = loadScene(sceneFile(dir, "out_%04d.csv"));
    ASSERT_TRUE(s.sequence);
    EXPECT_EQ(sequenceFrames(s), (std::vector<std::int64_t>{0, 10, 20}));
    EXPECT_EQ(s.frame, 0);
    EXPECT_EQ(s.bodies[0].path.filename(), "out_0000.csv");
    const Scene last = frameScene(s, 20);
    EXPECT_EQ(last.bodies[0].path.filename(), "out_0020.csv");
    EXPECT_DOUBLE_EQ(last.time, 20.0 / 24.0);  // fps 24 by default
    EXPECT_NEAR(buildParticles(last).particles.position[0].x, 20.0f, 1e-6);
    EXPECT_THROW(frameScene(s, 5), InputError);
}

TEST(Sequence, AMissingFrameIsNamedBeforeAnythingIsRead) {
    const fs::path dir = freshDir("sequence_missing");
    for (int n : {0, 10, 30}) writeFrame(dir / fmt::format("out_{:04d}.csv", n), n);
    const std::string e = errorOf(sceneFile(dir, "out_%04d.csv"));
    EXPECT_NE(e.find("frame 20 of the sequence out_%04d.csv is missing"), std::string::npos) << e;
    EXPECT_NE(e.find((dir / "out_0020.csv").string()), std::string::npos) << e;
    EXPECT_NE(e.find("body 'fluid'"), std::string::npos) << e;
    // Frames the range leaves out are not needed; a glob's missing number is named too.
    EXPECT_EQ(errorOf(sceneFile(dir, "out_%04d.csv"), {"sequence.last=10"}), "");
    const std::string glob = errorOf(sceneFile(dir, "out_*.csv"), {"sequence.step=5"});
    EXPECT_NE(glob.find("frame 5 of the sequence out_*.csv is missing"), std::string::npos) << glob;
    const std::string none = errorOf(sceneFile(dir, "nothing_*.csv"));
    EXPECT_NE(none.find("no file matches the sequence"), std::string::npos) << none;
}

// A scene file of a small ball seen from (0, -5, 0), its [sequence] table `sequence`.
fs::path cameraPathScene(const fs::path& dir, const std::string& name,
                         const std::string& sequence) {
    const fs::path file = dir / (name + ".toml");
    std::ofstream(file) << "[camera]\nposition = [0.0, -5.0, 0.0]\n"
                           "[[bodies]]\nshape = \"ball\"\nparticles = 50\n[sequence]\n"
                        << sequence;
    return file;
}

TEST(Sequence, TheCameraOrbitsAndFollowsKeyFrames) {
    const fs::path dir = freshDir("sequence_camera");
    const Scene s = loadScene(
        cameraPathScene(dir, "orbit", "last = 8\ncamera = \"orbit\"\norbit.degrees = 180.0\n"));
    // 180 degrees over frames 0 to 8 about +z (camera.up): frame 4 is a quarter turn.
    const glm::dvec3 p = cameraAtFrame(s, 4).position;
    EXPECT_NEAR(p.x, 5.0, 1e-9);
    EXPECT_NEAR(p.y, 0.0, 1e-9);
    EXPECT_NEAR(cameraAtFrame(s, 8).position.y, 5.0, 1e-9);

    const Scene k =
        loadScene(cameraPathScene(dir, "keys",
                                  "last = 10\ncamera = \"keys\"\n"
                                  "[[sequence.keys]]\nframe = 0\nposition = [0.0, -5.0, 0.0]\n"
                                  "[[sequence.keys]]\nframe = 5\nposition = [0.0, -5.0, 2.0]\n"
                                  "fov_y_deg = 30.0\n"
                                  "[[sequence.keys]]\nframe = 10\nposition = [0.0, -5.0, 0.0]\n"));
    EXPECT_NEAR(cameraAtFrame(k, 5).position.z, 2.0, 1e-12);  // through the keys
    EXPECT_NEAR(cameraAtFrame(k, 5).fovYDeg, 30.0, 1e-12);
    const double between = cameraAtFrame(k, 2).position.z;
    EXPECT_GT(between, 0.0);
    EXPECT_LT(between, 2.0);
    EXPECT_NEAR(cameraAtFrame(k, 10).position.z, 0.0, 1e-12);

    // A camera path that reaches its target at some frame is bad input, naming the frame.
    const std::string e =
        errorOf(cameraPathScene(dir, "bad",
                                "last = 3\ncamera = \"keys\"\n"
                                "[[sequence.keys]]\nframe = 0\nposition = [0.0, -5.0, 0.0]\n"
                                "[[sequence.keys]]\nframe = 2\nposition = [0.0, 0.0, 0.0]\n"));
    EXPECT_NE(e.find("at frame 2"), std::string::npos) << e;
}

TEST(BodyMotion, AMovingBodyIsWhereItsVelocityAndSpinPutIt) {
    const fs::path dir = freshDir("body_motion");
    const fs::path file = dir / "move.toml";
    std::ofstream(file) << "[[bodies]]\nname = \"ball\"\nshape = \"ball\"\nparticles = 400\n"
                           "center = [1.0, 0.0, 0.0]\nvelocity = [0.5, -1.0, 0.25]\n"
                           "spin = [0.0, 0.0, 90.0]\n"
                           "[sequence]\nlast = 4\nfps = 2.0\n";
    const Scene s0 = loadScene(file);
    const SceneParticles start = buildParticles(s0);
    const Scene s3 = frameScene(s0, 3);  // t = 1.5 s: moved by 1.5 v, turned by 135 degrees
    const SceneParticles moved = buildParticles(s3);
    ASSERT_EQ(start.particles.size(), moved.particles.size());
    const glm::dvec3 c(1.0, 0.0, 0.0), shift = 1.5 * glm::dvec3(0.5, -1.0, 0.25);
    const double a = 135.0 * M_PI / 180.0;
    for (std::size_t i = 0; i < start.particles.size(); ++i) {
        const glm::dvec3 r = glm::dvec3(start.particles.position[i]) - c;
        const glm::dvec3 expected = c + shift +
                                    glm::dvec3(std::cos(a) * r.x - std::sin(a) * r.y,
                                               std::sin(a) * r.x + std::cos(a) * r.y, r.z);
        // float positions: 1e-6 of the scene's extent of about 3.
        EXPECT_NEAR(glm::length(glm::dvec3(moved.particles.position[i]) - expected), 0.0, 5e-6);
    }
    // The body's uv frame moves with it: each particle keeps its texture coordinates.
    EXPECT_NEAR(glm::length(moved.bodies[0].center - (c + shift)), 0.0, 1e-12);
    for (std::size_t i = 0; i < start.particles.size(); i += 37)
        EXPECT_NEAR(glm::length(moved.particles.uv[i] - start.particles.uv[i]), 0.0, 1e-4);
}

TEST(BodyMotion, ChurnIsBoundedAndTheSameForTheSameFrame) {
    BodyDesc b;
    b.churn = 0.5;
    b.seed = 7;
    std::vector<glm::vec3> a(500, glm::vec3(0.0f)), again = a, next = a;
    BodyInfo info;
    applyMotion(b, 0.0, 3, a, 2.0, info);
    applyMotion(b, 0.0, 3, again, 2.0, info);
    applyMotion(b, 0.0, 4, next, 2.0, info);
    double largest = 0.0, mean = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        largest = std::max(largest, double(glm::length(a[i])));
        mean += glm::length(a[i]) / a.size();
    }
    EXPECT_LE(largest, 0.5 * 2.0 + 1e-6);  // churn x h
    // Uniform in the ball of radius R: mean distance 3R/4 = 0.75 (500 samples: +-0.02).
    EXPECT_NEAR(mean, 0.75, 0.05);
    EXPECT_EQ(a, again);
    EXPECT_NE(a, next);
}

}  // namespace
}  // namespace twinrender::core
