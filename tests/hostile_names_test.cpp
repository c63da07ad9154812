// A file the suite reads never decides where it writes: hostile scene names (path separators,
// "..", control characters, NUL, very long names, names unsafe on Windows, names differing
// only in case) given to every command that writes are exit 4 naming the file and key, and
// nothing is created outside the output folder the test names.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::hostile_names_test {

namespace tt = twinrender::test;
namespace fs = std::filesystem;

namespace {

// A scene of 300 particles at 24x16: renders in well under a second.
std::string sceneText(const std::string& nameLine) {
    return nameLine +
           "\n[camera]\nposition = [0.0, -4.0, 0.0]\nwidth = 24\nheight = 16\n"
           "[[materials]]\nname = \"rock\"\ndiffuse = [0.5, 0.5, 0.5]\n"
           "[[bodies]]\nname = \"ball\"\nshape = \"ball\"\nradius = 1.0\nparticles = 300\n"
           "material = \"rock\"\n";
}

// Every path under `dir`, except those under `dir/skip`.
std::set<std::string> treeOutside(const fs::path& dir, const fs::path& skip) {
    std::set<std::string> paths;
    for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator();
         ++it) {
        if (it->path() == skip) {
            it.disable_recursion_pending();
            continue;
        }
        paths.insert(fs::relative(it->path(), dir).string());
    }
    return paths;
}

// A test's folder: inputs in `in/`, the output folder three levels down, so that a name with
// "../.." that escaped it would land inside the case folder, where the test looks.
struct Case {
    fs::path dir, in, out;
    std::set<std::string> before;

    explicit Case(const std::string& name)
        : dir(tt::freshDir("hostile_names/" + name)), in(dir / "in"), out(dir / "a" / "b" / "out") {
        fs::create_directories(in);
        fs::create_directories(out.parent_path());
    }
    // Call when the inputs are written.
    void snapshot() { before = treeOutside(dir, out); }
    // Nothing new beside the output folder.
    void expectNothingOutsideOut() const {
        EXPECT_EQ(treeOutside(dir, out), before) << "files were made outside " << out;
    }
};

// TOML basic-string text for the name (escapes for ", \ and control characters).
std::string tomlString(const std::string& s) {
    std::string t = "\"";
    for (const char c : s) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\')
            t += std::string("\\") + c;
        else if (u < 0x20 || u == 0x7f)
            t += fmt::format("\\u{:04x}", u);
        else
            t += c;
    }
    return t + "\"";
}

struct Hostile {
    const char* label;
    std::string name;
};

std::vector<Hostile> hostileNames() {
    return {{"parent", ".."},
            {"dot", "."},
            {"escape", "../../escaped"},
            {"separator", "a/b"},
            {"backslash", "a\\b"},
            {"absolute", "/tmp/twinrender-hostile"},
            {"nul", std::string("a\0b", 3)},
            {"newline", "a\nb"},
            {"script", "x<script>alert(1)</script>"},
            {"windows_device", "CON"},
            {"trailing_dot", "name."},
            {"long", std::string(300, 'x')},
            {"empty", ""}};
}

}  // namespace

TEST(HostileNames, RenderRefusesEveryHostileSceneNameBeforeWriting) {
    for (const Hostile& h : hostileNames()) {
        Case c(std::string("render_") + h.label);
        tt::writeFile(c.in / "scene.toml", sceneText("name = " + tomlString(h.name)));
        c.snapshot();
        const auto r = tt::runTwinrender("render " + (c.in / "scene.toml").string() +
                                         " --renderer both --out " + c.out.string());
        EXPECT_EQ(r.exitCode, 4) << h.label << ": " << r.output;
        EXPECT_NE(r.output.find("scene.toml:1:"), std::string::npos) << h.label << r.output;
        EXPECT_NE(r.output.find("key 'name'"), std::string::npos) << h.label << r.output;
        EXPECT_NE(r.output.find("names its output folder"), std::string::npos) << r.output;
        EXPECT_EQ(tt::countFiles(c.out), 0u) << h.label;
        c.expectNothingOutsideOut();
    }
}

TEST(HostileNames, AnOverrideOfTheNameIsCheckedToo) {
    Case c("override");
    tt::writeFile(c.in / "scene.toml", sceneText("name = \"fine\""));
    c.snapshot();
    const auto r =
        tt::runTwinrender("render " + (c.in / "scene.toml").string() +
                          " --renderer raymarch --set name=../../escaped --out " + c.out.string());
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("--set name=../../escaped"), std::string::npos) << r.output;
    c.expectNothingOutsideOut();
}

TEST(HostileNames, AFileNameThatCannotNameAFolderNeedsANameKey) {
    Case c("file_stem");
    tt::writeFile(c.in / "nul.toml", sceneText(""));
    c.snapshot();
    const auto r = tt::runTwinrender("render " + (c.in / "nul.toml").string() +
                                     " --renderer raymarch --out " + c.out.string());
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("add a name = \"...\" line"), std::string::npos) << r.output;
    c.expectNothingOutsideOut();
}

TEST(HostileNames, RunSweepAndStudyRefuseThemBeforeAnythingRenders) {
    Case c("suite");
    tt::writeFile(c.in / "scene.toml", sceneText("name = \"../../escaped\""));
    c.snapshot();
    for (const std::string& args :
         {"run " + (c.in / "scene.toml").string(),
          "sweep " + (c.in / "scene.toml").string() + " --vary realtime.ssss.enabled=true,false",
          std::string("study depth_range --quick --set name=../../escaped")}) {
        const auto r = tt::runTwinrender(args + " --out " + c.out.string());
        EXPECT_EQ(r.exitCode, 4) << args << "\n" << r.output;
        EXPECT_NE(r.output.find("key 'name'"), std::string::npos) << args << "\n" << r.output;
        EXPECT_EQ(tt::countFiles(c.out), 0u) << args;
        c.expectNothingOutsideOut();
    }
}

TEST(HostileNames, ScenesWhoseFoldersWouldCollideAreRefusedBeforeAnythingRenders) {
    Case c("collide");
    tt::writeFile(c.in / "one.toml", sceneText("name = \"Planet\""));
    tt::writeFile(c.in / "two.toml", sceneText("name = \"planet\""));
    c.snapshot();
    auto r = tt::runTwinrender("run " + c.in.string() + " --out " + c.out.string());
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("name one output folder"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("one.toml"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("two.toml"), std::string::npos) << r.output;
    EXPECT_EQ(tt::countFiles(c.out), 0u);
    // A scene may not take the name of a file the run writes beside the scenes' folders.
    fs::remove(c.in / "two.toml");
    tt::writeFile(c.in / "one.toml", sceneText("name = \"Summary.json\""));
    r = tt::runTwinrender("run " + c.in.string() + " --out " + c.out.string());
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("beside the scenes' folders"), std::string::npos) << r.output;
    EXPECT_EQ(tt::countFiles(c.out), 0u);
    c.before = treeOutside(c.dir, c.out);  // one.toml changed, two.toml went
    c.expectNothingOutsideOut();
}

TEST(HostileNames, AnUnusualButSafeNameRendersIntoItsOwnFolder) {
    Case c("safe");
    const std::string name = "Planet (v2) + ring";
    tt::writeFile(c.in / "scene.toml", sceneText("name = " + tomlString(name)));
    c.snapshot();
    const auto r = tt::runTwinrender("render " + (c.in / "scene.toml").string() +
                                     " --renderer raymarch --out " + c.out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(fs::exists(c.out / name / "raymarch.exr"));
    c.expectNothingOutsideOut();
}

TEST(HostileNames, MergeReadsAndWritesOnlyInsideTheFoldersItWasGiven) {
    // A shard manifest whose report names a scene "../../escaped", beside a folder that such a
    // name would copy from.
    for (const std::string& name : {std::string("../../escaped"), std::string(".."),
                                    std::string("a/../../b"), std::string("/etc")}) {
        Case c("merge");
        const fs::path shard = c.in / "shard1";
        fs::create_directories(shard);
        fs::create_directories(c.dir / "escaped");
        tt::writeFile(c.dir / "escaped" / "secret.txt", "not the shard's");
        const nlohmann::json report = {{"scene", name},
                                       {"metrics", {{"beauty.flip", 0.1}}},
                                       {"checks", nlohmann::json::array()}};
        const nlohmann::json manifest = {{"format", "twinrender-shard"},
                                         {"version", 1},
                                         {"command", "run"},
                                         {"shard", 1},
                                         {"of", 1},
                                         {"settings", nlohmann::json::object()},
                                         {"scenes", {name}},
                                         {"reports", {report}},
                                         {"junit", false}};
        tt::writeFile(shard / "shard.json", manifest.dump());
        c.snapshot();
        const auto r = tt::runTwinrender("merge " + shard.string() + " --out " + c.out.string());
        EXPECT_EQ(r.exitCode, 4) << name << ": " << r.output;
        EXPECT_NE(r.output.find("shard.json: the scene name"), std::string::npos) << r.output;
        EXPECT_EQ(tt::countFiles(c.out), 0u) << name;
        c.expectNothingOutsideOut();
    }
}

TEST(HostileNames, MergeRefusesASweepCombinationFolderOutsideItsShard) {
    Case c("merge_sweep");
    const fs::path shard = c.in / "shard1";
    fs::create_directories(shard);
    const nlohmann::json manifest = {{"format", "twinrender-shard"},
                                     {"version", 1},
                                     {"command", "sweep"},
                                     {"shard", 1},
                                     {"of", 1},
                                     {"settings", nlohmann::json::object()},
                                     {"combinations", 1}};
    tt::writeFile(shard / "shard.json", manifest.dump());
    // A sweep.json as `sweep` writes it, but whose only row's folder leads out of the shard,
    // where a folder waits to be copied.
    fs::create_directories(c.dir / "escaped");
    tt::writeFile(c.dir / "escaped" / "secret.txt", "not the shard's");
    const nlohmann::json row = {{"index", 0},
                                {"dir", "../../escaped"},
                                {"settings", {{"realtime.ssss.enabled", "true"}}},
                                {"timings_ms", {{"total", 1.0}}},
                                {"metrics", {{"beauty.flip", 0.1}}}};
    const nlohmann::json sweep = {{"format", "twinrender-sweep"},
                                  {"version", 1},
                                  {"scene", "probe"},
                                  {"scene_file", "probe.toml"},
                                  {"mode", "realtime"},
                                  {"test", "realtime"},
                                  {"reference", "raymarch"},
                                  {"keys", {"realtime.ssss.enabled"}},
                                  {"metric", "beauty.flip"},
                                  {"frames", 1},
                                  {"combinations", 1},
                                  {"rows", {row}}};
    tt::writeFile(shard / "sweep.json", sweep.dump());
    c.snapshot();
    const auto r = tt::runTwinrender("merge " + shard.string() + " --out " + c.out.string());
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("the combination's folder '../../escaped'"), std::string::npos)
        << r.output;
    EXPECT_EQ(tt::countFiles(c.out), 0u);
    c.expectNothingOutsideOut();
}

TEST(HostileNames, BlessAndBaselinesRefuseSceneNamesThatAreNotFolderNames) {
    Case c("bless");
    const fs::path run = c.in / "run";
    fs::create_directories(run);
    const nlohmann::json summary = {
        {"scenes", {{{"name", "../../escaped"}, {"metrics", {{"beauty.flip", 0.1}}}}}}};
    tt::writeFile(run / "summary.json", summary.dump());
    const nlohmann::json baseline = {
        {"format", "twinrender-baseline"},
        {"version", 1},
        {"scenes", {{"../../escaped", {{"metrics", {{"beauty.flip", 0.1}}}}}}}};
    tt::writeFile(c.in / "baseline.json", baseline.dump());
    tt::writeFile(c.in / "scene.toml", sceneText("name = \"fine\""));
    c.snapshot();
    auto r = tt::runTwinrender("bless " + run.string() + " --out " + (c.out / "b.json").string());
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("scenes[0].name"), std::string::npos) << r.output;
    r = tt::runTwinrender("run " + (c.in / "scene.toml").string() + " --baseline " +
                          (c.in / "baseline.json").string() + " --out " + c.out.string());
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("baseline.json: key 'scenes."), std::string::npos) << r.output;
    EXPECT_EQ(tt::countFiles(c.out), 0u);
    c.expectNothingOutsideOut();
}

}  // namespace twinrender::e2e::hostile_names_test
