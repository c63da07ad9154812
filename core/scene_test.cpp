#include "core/scene.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"

namespace tc = twinrender::core;
namespace fs = std::filesystem;

namespace {

fs::path writeScene(const std::string& name, const std::string& text) {
    const fs::path dir = fs::path(::testing::TempDir()) / "scene_test";
    fs::create_directories(dir);
    const fs::path p = dir / (name + ".toml");
    std::ofstream(p) << text;
    return p;
}

const char* BASIC = R"(
description = "two bodies"
[camera]
position = [1.0, 2.0, 3.0]
width = 64
height = 32
[light]
direction = [0.0, 0.0, -2.0]
[[materials]]
name = "rock"
diffuse = [0.5, 0.4, 0.3]
specular = 0.2
[[materials]]
name = "grid"
diffuse = "procedural:latlong_grid"
[[bodies]]
name = "planet"
shape = "ball"
radius = 2.0
particles = 300
material = "grid"
[[bodies]]
name = "ring"
shape = "ring"
inner_radius = 2.5
outer_radius = 3.0
thickness = 0.1
normal = [0.0, 1.0, 1.0]
material = "rock"
[realtime]
ssss.enabled = false
[raymarch]
spp = 4
)";

std::string messageOf(const fs::path& p, std::vector<std::string> overrides = {}) {
    try {
        tc::loadScene(p, overrides);
    } catch (const tc::InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Scene, ReadsEveryDocumentedKey) {
    const tc::Scene s = tc::loadScene(writeScene("basic", BASIC));
    EXPECT_EQ(s.name, "basic");  // the file's stem
    EXPECT_EQ(s.description, "two bodies");
    EXPECT_EQ(s.camera.position, glm::dvec3(1.0, 2.0, 3.0));
    EXPECT_EQ(s.camera.width, 64);
    EXPECT_DOUBLE_EQ(s.camera.fovYDeg, 40.0);                  // default
    EXPECT_EQ(s.light.direction, glm::dvec3(0.0, 0.0, -1.0));  // normalised
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_EQ(s.materials[0].specular.value, glm::dvec3(0.2));
    EXPECT_EQ(s.materials[1].diffuse.kind, tc::TextureSource::Kind::Procedural);
    EXPECT_EQ(s.materials[1].diffuse.procedural, "latlong_grid");
    ASSERT_EQ(s.bodies.size(), 2u);
    EXPECT_EQ(s.bodies[0].materialIndex, 1u);
    EXPECT_EQ(s.bodies[1].shape, tc::Shape::Ring);
    EXPECT_NEAR(glm::length(s.bodies[1].normal), 1.0, 1e-12);
    EXPECT_TRUE(s.realtime.has("ssss.enabled"));
    EXPECT_EQ(s.raymarch.getInt("spp", 1, 1, 100), 4);
}

TEST(Scene, OverridesUseTheDottedKeysAndBodyNames) {
    const auto p = writeScene("overrides", BASIC);
    const tc::Scene s = tc::loadScene(
        p,
        std::vector<std::string>{"camera.width=160", "bodies.planet.particles=5000",
                                 "bodies.1.thickness=0.2", "realtime.depth=standard",
                                 "materials.rock.specular=[1, 0, 0]", "description=plain words"});
    EXPECT_EQ(s.camera.width, 160);
    EXPECT_EQ(s.bodies[0].particles, 5000);
    EXPECT_DOUBLE_EQ(s.bodies[1].thickness, 0.2);
    EXPECT_EQ(s.realtime.getString("depth", "log"), "standard");
    EXPECT_EQ(s.materials[0].specular.value, glm::dvec3(1.0, 0.0, 0.0));
    EXPECT_EQ(s.description, "plain words");
    // An override's messages name the override.
    const std::string m = messageOf(p, {"camera.fov_y_deg=500"});
    EXPECT_NE(m.find("--set camera.fov_y_deg=500"), std::string::npos) << m;
    EXPECT_NE(messageOf(p, {"bodies.moon.radius=1"}).find("no entry named 'moon'"),
              std::string::npos);
    EXPECT_NE(messageOf(p, {"novalue"}).find("KEY=VALUE"), std::string::npos);
}

TEST(Scene, OverrideErrorsNameTheOverrideAndTheKeyAsWritten) {
    const auto p = writeScene("override_errors", BASIC);
    // Out of range, of the wrong type or unknown, in every section the scene parser reads;
    // bodies and materials by name and by index.
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"camera.width=0", "key 'camera.width' is out of range: 0 (allowed: 1..16384)"},
        {"camera.fov_y_deg=wide", "key 'camera.fov_y_deg' has the wrong type: expected a number"},
        {"light.intensity=-1",
         "key 'light.intensity' is out of range: -1 (allowed: 0..1000000000)"},
        {"light.color=3",
         "key 'light.color' has the wrong type: expected an array of three numbers"},
        {"materials.rock.shininess=0",
         "key 'materials.rock.shininess' is out of range: 0 (allowed: 1..10000)"},
        {"materials.1.shininess=shiny", "key 'materials.1.shininess' has the wrong type"},
        {"bodies.planet.particles=2000000000",
         "key 'bodies.planet.particles' is out of range: 2000000000 (allowed: 1..50000000)"},
        {"bodies.1.inner_radius=-1",
         "key 'bodies.1.inner_radius' is out of range: -1 (allowed: 0.."},
        {"bodies.ring.thickness=thin", "key 'bodies.ring.thickness' has the wrong type"},
        {"bodies.planet.lattice=fcc",
         "key 'bodies.planet.lattice' is out of range: \"fcc\" (allowed: hcp | cubic | random)"},
        {"bodies.planet.center=[0, 0, \"x\"]",
         "key 'bodies.planet.center' must be an array of numbers"},
        {"bodies.planet.colour=1", "unknown key 'bodies.planet.colour'"},
        {"description=[1]", "key 'description' has the wrong type: expected a string"},
    };
    for (const auto& [assignment, error] : cases) {
        const std::string m = messageOf(p, {assignment});
        EXPECT_EQ(m.rfind("--set " + assignment + ": " + error, 0), 0u) << m;
    }
    // The sections the renderers and the comparison read keep where each value came from, a
    // table given whole by an override included.
    const tc::Scene s = tc::loadScene(
        p, std::vector<std::string>{"raymarch.spp=0", "realtime.shadow_map={resolution = 0}",
                                    "compare.thresholds.beauty.flip.max=high"});
    EXPECT_EQ(s.raymarch.describe("spp"), "--set raymarch.spp=0: key 'raymarch.spp'");
    EXPECT_EQ(s.realtime.describe("shadow_map.resolution"),
              "--set realtime.shadow_map={resolution = 0}: key 'realtime.shadow_map.resolution'");
    EXPECT_EQ(s.compare.describe("thresholds.beauty.flip.max"),
              "--set compare.thresholds.beauty.flip.max=high: key "
              "'compare.thresholds.beauty.flip.max'");
    // Keys the file gives keep their lines.
    EXPECT_NE(s.realtime.describe("ssss.enabled").find("override_errors.toml:"), std::string::npos);
    // A key of empty names or thousands deep (the fuzzer's find: a stack overflow while the
    // tables it built were read) is refused before any table is made.
    for (const std::string& key :
         {std::string("camera..width"), std::string(40, 'a') + std::string(40, '.')}) {
        const std::vector<std::string> sets = {key + "=1"};
        try {
            tc::loadScene(writeScene("deep", BASIC), sets);
            FAIL() << key;
        } catch (const tc::InputError& e) {
            EXPECT_NE(std::string(e.what()).find("not a key of the scene format"),
                      std::string::npos)
                << e.what();
        }
    }
}

TEST(Scene, RejectsWhatItDoesNotKnow) {
    std::string text = BASIC;
    EXPECT_NE(
        messageOf(writeScene("k1", text + "\n[lights]\nx = 1\n")).find("unknown table '[lights]'"),
        std::string::npos);
    EXPECT_NE(messageOf(writeScene("k2", "[[bodies]]\nshape = \"cube\"\n")).find("cube"),
              std::string::npos);
    EXPECT_NE(messageOf(writeScene("k3", "[[bodies]]\nshape = \"ring\"\ninner_radius = 1.0\n"))
                  .find("outer_radius"),
              std::string::npos);
    EXPECT_NE(messageOf(writeScene("k4", "[camera]\nnear = 2.0\nfar = 1.0\n[[bodies]]\n"))
                  .find("near < far"),
              std::string::npos);
    EXPECT_NE(messageOf(writeScene("k5", "name = \"x\"\n")).find("no [[bodies]]"),
              std::string::npos);
    EXPECT_NE(
        messageOf(
            writeScene("k6",
                       "[camera]\nup = [0.0, 1.0, 0.0]\nposition = [0.0, -4.0, 0.0]\n[[bodies]]\n"))
            .find("parallel"),
        std::string::npos);
    // The line of the offending key.
    const std::string m = messageOf(writeScene("k7", "[[bodies]]\nname = \"a\"\nradius = -1.0\n"));
    EXPECT_NE(m.find("k7.toml:3:"), std::string::npos) << m;
    EXPECT_NE(m.find("bodies[0].radius"), std::string::npos) << m;
    // A texture that is a device (read for ever) or missing, named by its key.
    const std::string device = messageOf(
        writeScene("k8", "[[materials]]\nname = \"m\"\ndiffuse = \"/dev/zero\"\n[[bodies]]\n"));
    EXPECT_NE(device.find("materials[0].diffuse': texture /dev/zero is not a file"),
              std::string::npos)
        << device;
    const std::string missing = messageOf(
        writeScene("k9", "[[materials]]\nname = \"m\"\ndiffuse = \"missing.png\"\n[[bodies]]\n"));
    EXPECT_NE(missing.find("missing.png does not exist"), std::string::npos) << missing;
    // A material name of another type (the fuzzer's find: it threw std::bad_variant_access).
    const std::string number =
        messageOf(writeScene("k10", "[[materials]]\nname = 6\n[[bodies]]\n"));
    EXPECT_NE(number.find("materials[0].name"), std::string::npos) << number;
}

TEST(Parameters, TypesRangesAndUnreadKeys) {
    tc::ParameterTable t("realtime", "scene.toml");
    t.set("ssss.enabled", true, "scene.toml:3:1");
    t.set("iterations", std::int64_t{3}, "scene.toml:4:1");
    t.set("radius", 2.5, "scene.toml:5:1");
    t.set("depth", std::string("log"), "scene.toml:6:1");
    t.set("typo", 1.0, "scene.toml:7:1");
    EXPECT_TRUE(t.getBool("ssss.enabled", false));
    EXPECT_EQ(t.getInt("iterations", 1, 1, 16), 3);
    EXPECT_DOUBLE_EQ(t.getDouble("iterations", 0.0, 0.0, 10.0), 3.0);  // integers are numbers
    EXPECT_DOUBLE_EQ(t.getDouble("missing", 7.0, 0.0, 10.0), 7.0);
    EXPECT_THROW(t.getDouble("radius", 0.0, 0.0, 1.0), tc::InputError);
    EXPECT_THROW(t.getInt("radius", 0, 0, 10), tc::InputError);  // 2.5 is not an integer
    EXPECT_THROW(t.getEnum("depth", "log", {"standard", "reversed"}), tc::InputError);
    EXPECT_THROW(t.getBool("depth", false), tc::InputError);
    try {
        t.checkAllRead();
        FAIL() << "the unread key was accepted";
    } catch (const tc::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("scene.toml:7:1: unknown key 'realtime.typo'"),
                  std::string::npos)
            << e.what();
    }
}

// bodies[].atmosphere = { ... }: a body's scattering shell; unknown keys under it are errors
// naming them, and a second body with an atmosphere is refused.
TEST(Scene, ReadsABodysAtmosphereAndRefusesASecond) {
    const tc::Scene s = tc::loadScene(
        writeScene("atmosphere",
                   "[[bodies]]\nname = \"planet\"\natmosphere = { thickness = 0.2, "
                   "scale_height = 0.05, scattering = [1.0, 2.0, 3.0], phase_g = 0.3 }\n"
                   "[[bodies]]\nname = \"moon\"\n"));
    ASSERT_TRUE(s.bodies[0].atmosphere);
    EXPECT_FALSE(s.bodies[1].atmosphere);
    EXPECT_DOUBLE_EQ(s.bodies[0].atmosphere->thickness, 0.2);
    EXPECT_DOUBLE_EQ(s.bodies[0].atmosphere->scaleHeight, 0.05);
    EXPECT_DOUBLE_EQ(s.bodies[0].atmosphere->scattering.z, 3.0);
    EXPECT_DOUBLE_EQ(s.bodies[0].atmosphere->phaseG, 0.3);
    EXPECT_EQ(s.bodies[0].atmosphere->steps, 32);
    EXPECT_FALSE(s.bodies[0].atmosphere->radius);
    EXPECT_NE(
        messageOf(writeScene("atmosphere_typo", "[[bodies]]\natmosphere = { thicknes = 0.2 }\n"))
            .find("atmosphere.thicknes"),
        std::string::npos);
    EXPECT_NE(messageOf(writeScene("atmosphere_zero",
                                   "[[bodies]]\natmosphere = { scale_height = 0.0 }\n"))
                  .find("scale_height"),
              std::string::npos);
    EXPECT_NE(messageOf(writeScene("atmosphere_two",
                                   "[[bodies]]\nname = \"a\"\natmosphere = "
                                   "{ steps = 8 }\n[[bodies]]\nname = \"b\"\n"
                                   "atmosphere = { steps = 8 }\n"))
                  .find("both have an atmosphere"),
              std::string::npos);
}
