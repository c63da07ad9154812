// Scale-out end to end: `run` and `sweep` split with --shard K/N and joined with `merge` give
// what one unsharded run gives (times aside: they are measured anew), and shards that do not
// belong together are refused. Small scenes (64x48) keep each run to seconds.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::merge_test {

namespace tt = twinrender::test;
using tt::count;
using tt::readJson;
using tt::readText;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string SCENES = ::twinrender::testing::sourceDir().string() + "/scenes/";
const std::string SMALL = " --set camera.width=64 --set camera.height=48";

// Times are measured anew by every run; the rest must be equal. Drops time.* metrics,
// timings_ms, and times in check messages' metrics (no check is on a time by default).
void dropTimes(json& j) {
    if (j.is_object()) {
        j.erase("timings_ms");
        j.erase("created");
        j.erase("command");
        if (j.contains("metrics") && j["metrics"].is_object())
            for (auto it = j["metrics"].begin(); it != j["metrics"].end();)
                it = it.key().rfind("time.", 0) == 0 ? j["metrics"].erase(it) : std::next(it);
        for (auto& [k, v] : j.items()) dropTimes(v);
    } else if (j.is_array()) {
        for (auto& v : j) dropTimes(v);
    }
}

}  // namespace

TEST(Merge, ShardedRunEqualsTheUnshardedRun) {
    const fs::path dir = tt::freshDir("merge_run");
    const std::string scenes =
        SCENES + "planet.toml " + SCENES + "contact.toml " + SCENES + "heated.toml" + SMALL;
    const auto whole = tt::runTwinrender("run " + scenes + " --out " + (dir / "whole").string() +
                                         " --junit " + (dir / "whole" / "junit.xml").string());
    ASSERT_NE(whole.exitCode, 4) << whole.output;
    for (const char* k : {"1", "2"}) {
        const auto shard = tt::runTwinrender("run " + scenes + " --shard " + k + "/2 --out " +
                                             (dir / (std::string("s") + k)).string() + " --junit " +
                                             (dir / (std::string("s") + k) / "junit.xml").string());
        ASSERT_NE(shard.exitCode, 4) << shard.output;
    }
    // Sorted by name (contact, heated, planet): shard 1 runs contact and planet, shard 2 heated.
    EXPECT_TRUE(fs::exists(dir / "s1" / "contact" / "metrics.json"));
    EXPECT_TRUE(fs::exists(dir / "s1" / "planet" / "metrics.json"));
    EXPECT_FALSE(fs::exists(dir / "s1" / "heated"));
    EXPECT_TRUE(fs::exists(dir / "s2" / "heated" / "metrics.json"));
    EXPECT_EQ(readJson(dir / "s2" / "shard.json")["shard"], 2);

    const auto merge =
        tt::runTwinrender("merge " + (dir / "s2").string() + " " + (dir / "s1").string() +
                          " --out " + (dir / "merged").string());
    EXPECT_EQ(merge.exitCode, whole.exitCode) << merge.output;
    json a = readJson(dir / "whole" / "summary.json"),
         b = readJson(dir / "merged" / "summary.json");
    ASSERT_FALSE(b.is_discarded()) << merge.output;
    dropTimes(a);
    dropTimes(b);
    EXPECT_EQ(a, b) << a.dump(1) << "\n---\n" << b.dump(1);
    for (const char* scene : {"planet", "contact", "heated"}) {
        json ma = readJson(dir / "whole" / scene / "metrics.json"),
             mb = readJson(dir / "merged" / scene / "metrics.json");
        dropTimes(ma);
        dropTimes(mb);
        EXPECT_EQ(ma, mb) << scene;
        for (const char* f : {"index.html", "realtime.exr", "raymarch.png", "error.beauty.png"})
            EXPECT_TRUE(fs::exists(dir / "merged" / scene / f)) << scene << "/" << f;
    }
    EXPECT_TRUE(fs::exists(dir / "merged" / "index.html"));
    // summary.md has no times and no command line: the same file.
    EXPECT_FALSE(readText(dir / "whole" / "summary.md").empty());
    EXPECT_EQ(readText(dir / "whole" / "summary.md"), readText(dir / "merged" / "summary.md"));
    EXPECT_EQ(count(readText(dir / "merged" / "junit.xml"), "<testcase "),
              count(readText(dir / "whole" / "junit.xml"), "<testcase "));
}

TEST(Merge, ShardedSweepEqualsTheUnshardedSweep) {
    const fs::path dir = tt::freshDir("merge_sweep");
    // Held to thresholds that pass the SSSS rows only (ꟻLIP about 0.096 with SSSS at radius
    // 0.6, 0.107 without, at 1500 particles), so the rows' verdicts must survive the merge.
    const fs::path bounds = dir / "thresholds.toml";
    tt::writeFile(bounds, "\"beauty.flip\" = { max = 0.1 }\n");
    // One reference cache for all three, as shards on a shared file system would use.
    const std::string sweep = "sweep " + SCENES + "planet.toml" + SMALL +
                              " --set bodies.planet.particles=1500"
                              " --set realtime.ssss.radius_scale=0.6"
                              " --vary realtime.ssss.enabled=true,false --vary "
                              "realtime.shadow_map.resolution=256,512,1024"
                              " --frames 1 --thresholds " +
                              bounds.string() + " --cache " + (dir / "cache").string();
    const auto whole = tt::runTwinrender(sweep + " --out " + (dir / "whole").string());
    ASSERT_EQ(whole.exitCode, 0) << whole.output;
    for (const char* k : {"1", "2", "3", "4"}) {
        // Shard 4 holds one failing combination only: whether one passes is the merge's to say.
        const auto shard = tt::runTwinrender(sweep + " --shard " + k + "/4 --out " +
                                             (dir / (std::string("s") + k)).string());
        ASSERT_EQ(shard.exitCode, 0) << shard.output;
        EXPECT_EQ(count(shard.output, "cache hit"), 1u) << shard.output;
    }
    EXPECT_EQ(readJson(dir / "s4" / "sweep.json")["rows"][0]["status"], "fail");
    // 6 combinations over 4 shards: 0 and 4, 1 and 5, 2, 3.
    EXPECT_EQ(readJson(dir / "s1" / "sweep.json")["rows"].size(), 2u);
    EXPECT_EQ(readJson(dir / "s4" / "sweep.json")["rows"].size(), 1u);
    const auto merge =
        tt::runTwinrender("merge " + (dir / "s1").string() + " " + (dir / "s3").string() + " " +
                          (dir / "s2").string() + " " + (dir / "s4").string() + " --out " +
                          (dir / "merged").string());
    ASSERT_EQ(merge.exitCode, 0) << merge.output;
    json a = readJson(dir / "whole" / "sweep.json"), b = readJson(dir / "merged" / "sweep.json");
    dropTimes(a);
    dropTimes(b);
    EXPECT_EQ(a, b) << a.dump(1) << "\n---\n" << b.dump(1);
    EXPECT_EQ(b["rows"].size(), 6u);
    for (const auto& row : b["rows"])
        EXPECT_EQ(row["status"],
                  row["settings"]["realtime.ssss.enabled"] == "true" ? "pass" : "fail");
    EXPECT_NE(merge.output.find("cheapest passing: "), std::string::npos) << merge.output;
    for (const auto& row : b["rows"])
        EXPECT_TRUE(fs::exists(dir / "merged" / row["dir"].get<std::string>() / "metrics.json"))
            << row["dir"];
    for (const char* f : {"sweep.csv", "sweep.svg", "index.html"})
        EXPECT_TRUE(fs::exists(dir / "merged" / f)) << f;
    // The CSVs differ in their times only: same header, same number of lines.
    const std::string ca = readText(dir / "whole" / "sweep.csv"),
                      cb = readText(dir / "merged" / "sweep.csv");
    EXPECT_EQ(ca.substr(0, ca.find('\n')), cb.substr(0, cb.find('\n')));
    EXPECT_EQ(count(ca, "\n"), count(cb, "\n"));
}

TEST(Merge, RefusesShardsThatDoNotBelongTogether) {
    const fs::path dir = tt::freshDir("merge_bad");
    // One scene over two shards: shard 2 has nothing to render, so these runs are quick.
    const std::string planet =
        "run " + SCENES + "planet.toml --set camera.width=32 --set camera.height=24";
    ASSERT_NE(tt::runTwinrender(planet + " --shard 1/2 --out " + (dir / "a1").string()).exitCode,
              4);
    ASSERT_NE(tt::runTwinrender(planet + " --shard 2/2 --out " + (dir / "a2").string()).exitCode,
              4);
    ASSERT_NE(tt::runTwinrender(planet + " --set realtime.ssss.enabled=false --shard 2/2 --out " +
                                (dir / "b2").string())
                  .exitCode,
              4);
    ASSERT_NE(tt::runTwinrender(planet + " --shard 2/3 --out " + (dir / "c2").string()).exitCode,
              4);

    const auto other = tt::runTwinrender("merge " + (dir / "a1").string() + " " +
                                         (dir / "b2").string() + " --out " + (dir / "m1").string());
    EXPECT_EQ(other.exitCode, 4) << other.output;
    EXPECT_NE(other.output.find("different settings"), std::string::npos) << other.output;
    EXPECT_NE(other.output.find("realtime.ssss.enabled=false"), std::string::npos) << other.output;
    const auto missing =
        tt::runTwinrender("merge " + (dir / "a1").string() + " --out " + (dir / "m2").string());
    EXPECT_EQ(missing.exitCode, 4) << missing.output;
    EXPECT_NE(missing.output.find("shard 2/2 is missing"), std::string::npos) << missing.output;
    const auto twice = tt::runTwinrender("merge " + (dir / "a1").string() + " " +
                                         (dir / "a1").string() + " --out " + (dir / "m3").string());
    EXPECT_EQ(twice.exitCode, 4) << twice.output;
    const auto count3 =
        tt::runTwinrender("merge " + (dir / "a1").string() + " " + (dir / "c2").string() +
                          " --out " + (dir / "m4").string());
    EXPECT_EQ(count3.exitCode, 4) << count3.output;
    const auto notShard =
        tt::runTwinrender("merge " + (dir / "m1").string() + " --out " + (dir / "m5").string());
    EXPECT_EQ(notShard.exitCode, 4) << notShard.output;
    EXPECT_FALSE(fs::exists(dir / "m1" / "summary.json"));
    // The good pair merges.
    const auto good = tt::runTwinrender("merge " + (dir / "a1").string() + " " +
                                        (dir / "a2").string() + " --out " + (dir / "m6").string());
    EXPECT_NE(good.exitCode, 4) << good.output;
    EXPECT_EQ(readJson(dir / "m6" / "summary.json")["scenes"].size(), 1u);
}

}  // namespace twinrender::e2e::merge_test
