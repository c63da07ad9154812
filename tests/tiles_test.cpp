// One reference frame split across machines end to end: `render --tiles K/N` and
// `run --tiles K/N` render parts that `merge` joins into what one render or one run writes, bit
// for bit (times aside), whatever the parts' thread counts; parts that do not belong together
// are refused with exit 4 and nothing written. Small scenes (64x48, a few thousand particles)
// keep each command to about a second.
#include <gtest/gtest.h>

#include <cstring>
#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::tiles_test {

namespace tt = twinrender::test;
using tt::readJson;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string TEST_SCENES = ::twinrender::testing::sourceDir().string() + "/tests/scenes/";
// The ball on a slab with ambient occlusion and 2 samples per pixel: its occlusion rays and
// jitter are seeded per pixel and sample, so a part must seed each pixel as the whole frame
// does.
const std::string OCCLUDED = TEST_SCENES +
                             "ball_on_slab.toml --set camera.width=64 --set camera.height=48"
                             " --set raymarch.spp=2 --set raymarch.ao_samples=16"
                             " --set bodies.slab.particles=1200 --set bodies.ball.particles=600";
// The lamp over a slab: the emitters' rays, their standard error (a mean over the frame) and
// the count of emitting bodies (the same in every part).
const std::string LIT = TEST_SCENES +
                        "lamp_over_slab.toml --set camera.width=64 --set camera.height=48"
                        " --set raymarch.emissive_samples=4 --set bodies.slab.particles=1200";

// Every channel of two EXRs, bit for bit.
void expectSameBits(const fs::path& a, const fs::path& b) {
    const auto x = twinrender::core::readImage(a), y = twinrender::core::readImage(b);
    ASSERT_EQ(x.channelNames(), y.channelNames()) << b;
    ASSERT_EQ(x.width(), y.width());
    ASSERT_EQ(x.height(), y.height());
    for (int c = 0; c < x.channelCount(); ++c) {
        const std::vector<float> p = x.plane(c), q = y.plane(c);
        EXPECT_EQ(std::memcmp(p.data(), q.data(), p.size() * sizeof(float)), 0)
            << b << ": channel " << x.channelNames()[c] << " differs from " << a;
    }
}

// A render's JSON without what a merge measures anew: the times, the parts, the device (the
// threads it names).
json withoutTimes(const fs::path& file) {
    json j = readJson(file);
    for (const char* key : {"timings_ms", "tiles", "device"}) j.erase(key);
    return j;
}

tt::CommandResult renderPart(const std::string& scene, const std::string& part, const fs::path& out,
                             const std::string& more = "") {
    return tt::runTwinrender("render " + scene + " --tiles " + part + " --out " + out.string() +
                             more);
}

}  // namespace

TEST(Tiles, ThreePartsJoinToTheWholeRenderBitForBit) {
    const fs::path dir = tt::freshDir("tiles_three");
    const auto whole = tt::runTwinrender("render " + OCCLUDED + " --renderer raymarch --out " +
                                         (dir / "whole").string());
    ASSERT_EQ(whole.exitCode, 0) << whole.output;
    for (const char* k : {"1", "2", "3"}) {
        const auto r = renderPart(OCCLUDED, std::string(k) + "/3", dir / k);
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    // A part says which it is, and holds its rows alone: 48 rows in tiles of 16, one each.
    const fs::path part2 = dir / "2" / "ball_on_slab";
    EXPECT_EQ(readJson(part2 / "raymarch.json")["tile"]["part"], 2);
    EXPECT_EQ(readJson(part2 / "raymarch.json")["tile"]["of"], 3);
    EXPECT_EQ(readJson(dir / "2" / "shard.json")["split"], "tiles");
    EXPECT_EQ(twinrender::core::readImage(part2 / "raymarch.exr").height(), 16);
    EXPECT_FALSE(fs::exists(part2 / "raymarch.png"));

    const auto merge =
        tt::runTwinrender("merge " + (dir / "3").string() + " " + (dir / "1").string() + " " +
                          (dir / "2").string() + " --out " + (dir / "merged").string());
    ASSERT_EQ(merge.exitCode, 0) << merge.output;
    const fs::path a = dir / "whole" / "ball_on_slab", b = dir / "merged" / "ball_on_slab";
    expectSameBits(a / "raymarch.exr", b / "raymarch.exr");
    expectSameBits(a / "raymarch.png", b / "raymarch.png");
    // The counters too: the occlusion's rays and its standard error, a mean over the frame.
    const json ja = withoutTimes(a / "raymarch.json"), jb = withoutTimes(b / "raymarch.json");
    EXPECT_EQ(ja, jb) << ja.dump(1) << "\n---\n" << jb.dump(1);
    EXPECT_GT(ja["counters"]["ao_standard_error"].get<double>(), 0.0);
    EXPECT_EQ(readJson(b / "raymarch.json")["tiles"].size(), 3u);
}

TEST(Tiles, PartsOfOtherThreadCountsJoinToTheSameBits) {
    const fs::path dir = tt::freshDir("tiles_threads");
    const auto whole = tt::runTwinrender(
        "render " + LIT + " --renderer raymarch --threads 2 --out " + (dir / "whole").string());
    ASSERT_EQ(whole.exitCode, 0) << whole.output;
    ASSERT_EQ(renderPart(LIT, "1/2", dir / "1", " --threads 1").exitCode, 0);
    ASSERT_EQ(renderPart(LIT, "2/2", dir / "2", " --threads 2").exitCode, 0);
    const auto merge =
        tt::runTwinrender("merge " + (dir / "1").string() + " " + (dir / "2").string() + " --out " +
                          (dir / "merged").string());
    ASSERT_EQ(merge.exitCode, 0) << merge.output;
    const fs::path a = dir / "whole" / "lamp_over_slab", b = dir / "merged" / "lamp_over_slab";
    expectSameBits(a / "raymarch.exr", b / "raymarch.exr");
    const json ja = withoutTimes(a / "raymarch.json"), jb = withoutTimes(b / "raymarch.json");
    EXPECT_EQ(ja, jb) << ja.dump(1) << "\n---\n" << jb.dump(1);
    EXPECT_GT(ja["counters"]["irradiance_standard_error"].get<double>(), 0.0);
    // The merged device names both parts' thread counts.
    const std::string device = readJson(b / "raymarch.json")["device"];
    EXPECT_NE(device.find("(1 threads); "), std::string::npos) << device;
}

TEST(Tiles, PartsBeyondTheRowsOfTilesAreEmptyAndJoinAlike) {
    const fs::path dir = tt::freshDir("tiles_empty");
    // 32 pixels high: two rows of tiles of 16 for three parts.
    const std::string two = TEST_SCENES +
                            "one_sphere.toml --set camera.width=32 "
                            "--set camera.height=32";
    ASSERT_EQ(tt::runTwinrender("render " + two + " --renderer raymarch --out " +
                                (dir / "whole").string())
                  .exitCode,
              0);
    for (const char* k : {"1", "2", "3"})
        ASSERT_EQ(renderPart(two, std::string(k) + "/3", dir / k).exitCode, 0);
    EXPECT_FALSE(fs::exists(dir / "3" / "one_sphere" / "raymarch.exr"));
    const auto merge =
        tt::runTwinrender("merge " + (dir / "1").string() + " " + (dir / "2").string() + " " +
                          (dir / "3").string() + " --out " + (dir / "merged").string());
    ASSERT_EQ(merge.exitCode, 0) << merge.output;
    expectSameBits(dir / "whole" / "one_sphere" / "raymarch.exr",
                   dir / "merged" / "one_sphere" / "raymarch.exr");
}

TEST(Tiles, ARunInTilesMergesToTheWholeRun) {
    const fs::path dir = tt::freshDir("tiles_run");
    const auto whole = tt::runTwinrender("run " + OCCLUDED + " --out " + (dir / "whole").string());
    ASSERT_NE(whole.exitCode, 4) << whole.output;
    for (const char* k : {"1", "2"}) {
        const auto r = tt::runTwinrender("run " + OCCLUDED + " --tiles " + k + "/2 --threads " + k +
                                         " --out " + (dir / k).string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        // A tile job renders its part of the reference and nothing else.
        EXPECT_FALSE(fs::exists(dir / k / "summary.json"));
        EXPECT_EQ(r.output.find("realtime"), std::string::npos) << r.output;
    }
    const auto merge =
        tt::runTwinrender("merge " + (dir / "1").string() + " " + (dir / "2").string() + " --out " +
                          (dir / "merged").string());
    EXPECT_EQ(merge.exitCode, whole.exitCode) << merge.output;
    EXPECT_NE(merge.output.find("cache hit"), std::string::npos) << merge.output;
    const fs::path a = dir / "whole" / "ball_on_slab", b = dir / "merged" / "ball_on_slab";
    expectSameBits(a / "raymarch.exr", b / "raymarch.exr");
    // Every metric but the times, as one run measures them.
    json ma = readJson(a / "metrics.json"), mb = readJson(b / "metrics.json");
    ASSERT_FALSE(mb.is_discarded()) << merge.output;
    for (json* m : {&ma, &mb})
        for (auto it = (*m)["metrics"].begin(); it != (*m)["metrics"].end();)
            it = it.key().rfind("time.", 0) == 0 ? (*m)["metrics"].erase(it) : std::next(it);
    EXPECT_EQ(ma["metrics"], mb["metrics"]);
    EXPECT_EQ(tt::readText(dir / "whole" / "summary.md"),
              tt::readText(dir / "merged" / "summary.md"));
}

TEST(Tiles, ASweepInTilesMergesToTheWholeSweep) {
    const fs::path dir = tt::freshDir("tiles_sweep");
    // The raymarcher's convergence: both combinations against one tight reference, which the
    // tiles split.
    const std::string sweep = "sweep " + TEST_SCENES +
                              "one_sphere.toml --set camera.width=48 --set camera.height=48"
                              " --vary raymarch.spp=1,2";
    const auto whole = tt::runTwinrender(sweep + " --out " + (dir / "whole").string());
    ASSERT_EQ(whole.exitCode, 0) << whole.output;
    for (const char* k : {"1", "2"}) {
        const auto r =
            tt::runTwinrender(sweep + " --tiles " + k + "/2 --out " + (dir / k).string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_FALSE(fs::exists(dir / k / "sweep.json"));
    }
    const auto merge =
        tt::runTwinrender("merge " + (dir / "2").string() + " " + (dir / "1").string() + " --out " +
                          (dir / "merged").string());
    ASSERT_EQ(merge.exitCode, 0) << merge.output;
    json a = readJson(dir / "whole" / "sweep.json"), b = readJson(dir / "merged" / "sweep.json");
    ASSERT_FALSE(b.is_discarded()) << merge.output;
    // The times are measured anew.
    for (json* j : {&a, &b}) {
        j->erase("created");
        j->erase("command");
        for (json& row : (*j)["rows"]) {
            row.erase("timings_ms");
            for (auto it = row["metrics"].begin(); it != row["metrics"].end();)
                it = it.key().rfind("time.", 0) == 0 ? row["metrics"].erase(it) : std::next(it);
        }
    }
    EXPECT_EQ(a, b) << a.dump(1) << "\n---\n" << b.dump(1);
}

TEST(Tiles, RefusesPartsThatDoNotBelongTogether) {
    const fs::path dir = tt::freshDir("tiles_refused");
    // Three rows of tiles of 16 pixels, one a part.
    const std::string tiny = TEST_SCENES +
                             "one_sphere.toml --set camera.width=32 "
                             "--set camera.height=48";
    for (const char* k : {"1", "2", "3"})
        ASSERT_EQ(renderPart(tiny, std::string(k) + "/3", dir / k).exitCode, 0);
    ASSERT_EQ(renderPart(tiny, "3/3", dir / "spp", " --set raymarch.spp=2").exitCode, 0);
    const auto refused = [&](const std::string& inputs, const std::string& says) {
        const fs::path out = dir / "out";
        fs::remove_all(out);
        const auto r = tt::runTwinrender("merge " + inputs + " --out " + out.string());
        EXPECT_EQ(r.exitCode, 4) << r.output;
        EXPECT_NE(r.output.find(says), std::string::npos) << r.output;
        EXPECT_EQ(tt::countFiles(out), 0u) << inputs;
    };
    const std::string p1 = (dir / "1").string(), p2 = (dir / "2").string(),
                      p3 = (dir / "3").string();
    refused(p1 + " " + p2, "tile 3/3 is missing");
    refused(p1 + " " + p2 + " " + p2 + " " + p3, "are both tile 2/3");
    refused(p1 + " " + p2 + " " + (dir / "spp").string(), "raymarch.spp=2");
    // A part of another build: its frame's account names the build.
    fs::copy(dir / "2", dir / "build", fs::copy_options::recursive);
    json manifest = readJson(dir / "build" / "shard.json");
    manifest["references"][0]["what"]["build"] = "0.0.0+another";
    manifest["references"][0]["key"] = "0123456789abcdef";
    tt::writeFile(dir / "build" / "shard.json", manifest.dump());
    refused(p1 + " " + (dir / "build").string() + " " + p3, "/build");
    // A part whose image is gone.
    fs::copy(dir / "3", dir / "cut", fs::copy_options::recursive);
    fs::remove(dir / "cut" / "one_sphere" / "raymarch.exr");
    refused(p1 + " " + p2 + " " + (dir / "cut").string(), "missing");
    // Tiles of a frame and shards of a run's scenes.
    const std::string run = "run " + tiny + " --out ";
    ASSERT_EQ(tt::runTwinrender(run + (dir / "t1").string() + " --tiles 1/2").exitCode, 0);
    ASSERT_NE(tt::runTwinrender(run + (dir / "s2").string() + " --shard 2/2").exitCode, 4);
    refused((dir / "t1").string() + " " + (dir / "s2").string(), "--shard");
    refused(p1 + " " + (dir / "t1").string(), "merge the parts of one command");

    // Options that cannot split: exit 4 naming --tiles, nothing written.
    const auto realtime = renderPart(tiny, "1/2", dir / "rt", " --renderer realtime");
    EXPECT_EQ(realtime.exitCode, 4) << realtime.output;
    EXPECT_NE(realtime.output.find("--tiles 1/2 with --renderer realtime"), std::string::npos)
        << realtime.output;
    EXPECT_EQ(tt::countFiles(dir / "rt"), 0u);
    const auto bad = renderPart(tiny, "4/3", dir / "bad");
    EXPECT_EQ(bad.exitCode, 4) << bad.output;
    EXPECT_NE(bad.output.find("--tiles 4/3"), std::string::npos) << bad.output;
    const auto both = tt::runTwinrender(run + (dir / "both").string() + " --tiles 1/2 --shard 1/2");
    EXPECT_EQ(both.exitCode, 4) << both.output;
    EXPECT_EQ(tt::countFiles(dir / "both"), 0u);
}

TEST(Tiles, AMergeRefusesTilesOfAnotherSceneThanTheRunTakesNow) {
    const fs::path dir = tt::freshDir("tiles_changed");
    const fs::path scene = dir / "sphere.toml";
    fs::copy_file(TEST_SCENES + "one_sphere.toml", scene);
    fs::copy_file(TEST_SCENES + "one_particle.csv", dir / "one_particle.csv");
    const std::string run =
        "run " + scene.string() + " --set camera.width=32 --set camera.height=24";
    for (const char* k : {"1", "2"})
        ASSERT_EQ(
            tt::runTwinrender(run + " --tiles " + k + "/2 --out " + (dir / k).string()).exitCode,
            0);
    // The scene file changed between the tiles and the merge.
    tt::writeFile(scene, tt::readText(scene) + "\n# changed\n");
    const auto r = tt::runTwinrender("merge " + (dir / "1").string() + " " + (dir / "2").string() +
                                     " --out " + (dir / "m").string());
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("another reference than the run takes now"), std::string::npos)
        << r.output;
    EXPECT_EQ(tt::countFiles(dir / "m"), 0u);
}

}  // namespace twinrender::e2e::tiles_test
