// `twinrender export`: what another renderer needs to draw the reference's frame
// (docs/external.md). The particles read back equal the ones the renderers draw, the matrices
// put every particle on the pixel core::Camera projects it to, the textures are the materials'
// own, and a sequence exports each frame of its range.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/image_io.h"
#include "core/particle_file.h"
#include "core/particles.h"
#include "core/scene.h"
#include "core/texture.h"
#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::export_test {

namespace tt = twinrender::test;
namespace fs = std::filesystem;
namespace core = twinrender::core;

namespace {

const std::string SCENES = ::twinrender::testing::sourceDir().string() + "/scenes/";

glm::dmat4 matrix(const nlohmann::json& rows) {
    glm::dmat4 m(0.0);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m[c][r] = rows[r][c].get<double>();
    return m;
}

}  // namespace

TEST(Export, TheParticlesCameraAndTexturesAreTheRenderersOwn) {
    const fs::path dir = tt::freshDir("export_planet");
    const std::string sets = " --set camera.width=96 --set camera.height=72";
    const auto r =
        tt::runTwinrender("export " + SCENES + "planet.toml --out " + dir.string() + sets);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json j = tt::readJson(dir / "planet" / "scene.json");
    EXPECT_EQ(j["format"], "twinrender-export");
    EXPECT_EQ(j["version"], 1);
    ASSERT_EQ(j["frames"].size(), 1u);

    const std::vector<std::string> overrides = {"camera.width=96", "camera.height=72"};
    const core::Scene scene = core::loadScene(SCENES + "planet.toml", overrides);
    const core::SceneParticles particles = core::buildParticles(scene);
    const core::ParticleFileData ply =
        core::readParticleFile(dir / "planet" / j["frames"][0]["particles"].get<std::string>());
    ASSERT_EQ(ply.size(), particles.particles.size());
    const core::ParticleSet& ps = particles.particles;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        ASSERT_EQ(ply.position[i], glm::dvec3(ps.position[i])) << i;
        ASSERT_EQ(ply.h[i], double(ps.h[i])) << i;
        ASSERT_EQ(ply.uv[i], glm::dvec2(ps.uv[i])) << i;
        ASSERT_EQ(ply.body[i], std::int64_t(ps.body[i])) << i;
    }

    // The matrices take every particle in view to the pixel core::Camera projects it to
    // (row 0 at the top, pixel centres at +0.5), and its depth to OpenGL's NDC z.
    const core::Camera camera(scene.camera);
    const glm::dmat4 view = matrix(j["camera"]["view_matrix"]);
    const glm::dmat4 projection = matrix(j["camera"]["projection_matrix"]);
    int seen = 0;
    for (std::size_t i = 0; i < ps.size(); i += 97) {
        const glm::dvec3 p(ps.position[i]);
        const double z = camera.eyeDepth(p);
        if (z < scene.camera.near) continue;
        const glm::dvec4 eye = view * glm::dvec4(p, 1.0);
        EXPECT_NEAR(-eye.z, z, 1e-9 * (1.0 + z)) << i;
        const glm::dvec4 clip = projection * eye;
        const glm::dvec2 pixel((clip.x / clip.w + 1.0) * 0.5 * scene.camera.width,
                               (1.0 - clip.y / clip.w) * 0.5 * scene.camera.height);
        const glm::dvec2 expected = camera.project(p);
        // Double arithmetic both ways: far below a thousandth of a pixel.
        EXPECT_NEAR(pixel.x, expected.x, 1e-6) << i;
        EXPECT_NEAR(pixel.y, expected.y, 1e-6) << i;
        const double n = scene.camera.near, f = scene.camera.far;
        EXPECT_NEAR(clip.z / clip.w, (f + n) / (f - n) - 2.0 * f * n / ((f - n) * z), 1e-9) << i;
        ++seen;
    }
    EXPECT_GT(seen, 10);

    // The textures baked to images are the materials' own.
    const std::vector<core::Material> materials = core::loadMaterials(scene);
    ASSERT_EQ(j["materials"].size(), materials.size());
    for (std::size_t m = 0; m < materials.size(); ++m) {
        const core::Image diffuse =
            core::readImage(dir / "planet" / j["materials"][m]["diffuse"].get<std::string>());
        const core::Image& own = materials[m].diffuse.image();
        ASSERT_EQ(diffuse.width(), own.width());
        ASSERT_EQ(diffuse.height(), own.height());
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(diffuse.at(own.width() / 2, own.height() / 2, c),
                      own.at(own.width() / 2, own.height() / 2, c));
    }
    EXPECT_EQ(j["light"]["intensity"], scene.light.intensity);
}

TEST(Export, ASequenceExportsEachFrameOfItsRange) {
    const fs::path dir = tt::freshDir("export_sequence");
    const auto r = tt::runTwinrender(
        "export " + SCENES + "collision_sequence.toml --frames 10:11 " + "--out " + dir.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json j = tt::readJson(dir / "collision_sequence" / "scene.json");
    ASSERT_EQ(j["frames"].size(), 2u);
    EXPECT_EQ(j["frames"][0]["particles"], "0010/particles.ply");
    EXPECT_EQ(j["frames"][1]["particles"], "0011/particles.ply");
    const auto a = core::readParticleFile(dir / "collision_sequence" / "0010" / "particles.ply");
    const auto b = core::readParticleFile(dir / "collision_sequence" / "0011" / "particles.ply");
    ASSERT_GT(a.size(), 0u);
    EXPECT_NE(a.position, b.position);  // the bodies collide: the particles move
}

TEST(Export, AStillSceneHasNoFramesToChoose) {
    const fs::path dir = tt::freshDir("export_bad");
    const auto r =
        tt::runTwinrender("export " + SCENES + "planet.toml --frames 1:2 --out " + dir.string());
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("not a sequence"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "planet" / "scene.json"));
}

}  // namespace twinrender::e2e::export_test
