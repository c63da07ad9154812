// `twinrender sweep` end to end, on the planet scene at 64x48 so each sweep takes seconds:
// the rows of the cartesian product, the Pareto front and the chart, the reference cache, the
// raymarcher's convergence sweep, the combinations held to thresholds, and bad input.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "report/svg_chart.h"
#include "report/testdata/xml_check.h"
#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::sweep_test {

namespace tt = twinrender::test;
using tt::count;
using tt::readJson;
using tt::readText;
using tt::selftestInBrowser;
namespace tc = twinrender::report;
namespace fs = std::filesystem;

namespace {

const std::string SCENES = ::twinrender::testing::sourceDir().string() + "/scenes/";
// SSSS at radius 0.6 (its default before the gradient normals), whose effect on the metrics
// these small images show clearly: the threshold tests tell its rows from the others.
const std::string SMALL =
    " --set camera.width=64 --set camera.height=48 --set bodies.planet.particles=1500"
    " --set realtime.ssss.radius_scale=0.6";
const std::string GRID =
    " --vary realtime.ssss.enabled=true,false --vary realtime.shadow_map.resolution=256,1024";

// The line of the output that starts with `prefix`, without its end; empty when none does.
std::string lineStarting(const std::string& text, const std::string& prefix) {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (line.rfind(prefix, 0) == 0) return line;
    return "";
}

}  // namespace

TEST(Sweep, RowsParetoFrontChartAndACachedReference) {
    const fs::path out = tt::freshDir("sweep_grid");
    const auto r = tt::runTwinrender("sweep " + SCENES + "planet.toml" + SMALL + GRID +
                                     " --frames 2 --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // One reference for the four combinations: varying realtime.* keys shares it.
    EXPECT_EQ(count(r.output, "rendered in"), 1u) << r.output;
    EXPECT_EQ(count(r.output, "cache hit"), 0u) << r.output;

    const auto sweep = readJson(out / "sweep.json");
    ASSERT_FALSE(sweep.is_discarded());
    ASSERT_EQ(sweep["rows"].size(), 4u);  // 2 x 2
    EXPECT_EQ(sweep["keys"],
              (nlohmann::json{"realtime.ssss.enabled", "realtime.shadow_map.resolution"}));
    EXPECT_EQ(sweep["metric"], "beauty.flip");
    EXPECT_EQ(sweep["better"], "lower");
    EXPECT_EQ(sweep["frames"], 2);
    // Cartesian order, the first key slowest.
    const char* expected[4][2] = {
        {"true", "256"}, {"true", "1024"}, {"false", "256"}, {"false", "1024"}};
    std::vector<tc::ChartPoint> points;
    for (std::size_t i = 0; i < 4; ++i) {
        const auto& row = sweep["rows"][i];
        EXPECT_EQ(row["index"], i);
        EXPECT_EQ(row["settings"]["realtime.ssss.enabled"], expected[i][0]);
        EXPECT_EQ(row["settings"]["realtime.shadow_map.resolution"], expected[i][1]);
        EXPECT_EQ(row["reference_key"], sweep["rows"][0]["reference_key"]);
        for (const char* stage : {"total", "shadow", "gbuffer", "ssss", "shade", "post"})
            EXPECT_TRUE(row["timings_ms"].contains(stage)) << stage;
        for (const char* m : {"beauty.flip", "beauty.ssim", "normal.mean_deg", "shadow.iou"})
            EXPECT_TRUE(row["metrics"][m].is_number()) << m;
        EXPECT_TRUE(fs::exists(out / row["dir"].get<std::string>() / "metrics.json"));
        EXPECT_TRUE(fs::exists(out / row["dir"].get<std::string>() / "realtime.png"));
        points.push_back({row["timings_ms"]["total"].get<double>(),
                          row["metrics"]["beauty.flip"].get<double>(), ""});
    }
    // SSSS off makes the particles show: a larger ꟻLIP error at 1024 shadow texels too.
    EXPECT_GT(sweep["rows"][3]["metrics"]["beauty.flip"].get<double>(),
              sweep["rows"][1]["metrics"]["beauty.flip"].get<double>());

    // CSV: a header and a line per row, the settings in their columns.
    std::istringstream csv(readText(out / "sweep.csv"));
    std::string header, line;
    std::getline(csv, header);
    EXPECT_EQ(header.rfind(
                  "index,realtime.ssss.enabled,realtime.shadow_map.resolution,time.total_ms,", 0),
              0u)
        << header;
    EXPECT_NE(header.find("beauty.flip"), std::string::npos);
    std::vector<std::string> lines;
    while (std::getline(csv, line)) lines.push_back(line);
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(lines[2].rfind("2,false,256,", 0), 0u) << lines[2];

    // The chart: well-formed, one marker per row (and two in the legend), the front marked.
    const std::string svg = readText(out / "sweep.svg");
    const auto xml = tt::checkXml(svg);
    ASSERT_EQ(xml.error, "") << svg;
    EXPECT_EQ(xml.classCounts.at("point"), 4 + 2);
    const auto front = tc::paretoFront(points, true);
    EXPECT_GE(front.size(), 1u);
    EXPECT_EQ(xml.classCounts.at("pareto-point"), static_cast<int>(front.size()) + 1);
    EXPECT_NE(svg.find("ms"), std::string::npos);
    EXPECT_NE(svg.find("beauty.flip (lower is better)"), std::string::npos);
    // The page: chart, table, command line.
    const std::string html = readText(out / "index.html");
    EXPECT_NE(html.find("<img src=\"sweep.svg\""), std::string::npos);
    EXPECT_NE(html.find("--vary realtime.ssss.enabled=true,false"), std::string::npos);
    EXPECT_EQ(count(html, "class=\"thumb\""), 4u);
    // In a browser: the chart and the four thumbnails load, no script error.
    const std::string selftest =
        selftestInBrowser(out / "index.html", tt::freshDir("sweep_browser"));
    if (!selftest.empty()) {
        EXPECT_EQ(selftest, "selftest: ok (5 images)");
    }

    // The same sweep again: the reference comes from the cache, untouched.
    const std::string key = sweep["rows"][0]["reference_key"];
    const fs::path cached = out / "reference_cache" / key / "raymarch.exr";
    ASSERT_TRUE(fs::exists(cached));
    const auto mtime = fs::last_write_time(cached);
    const auto again = tt::runTwinrender("sweep " + SCENES + "planet.toml" + SMALL + GRID +
                                         " --frames 1 --out " + out.string());
    ASSERT_EQ(again.exitCode, 0) << again.output;
    EXPECT_EQ(count(again.output, "cache hit"), 1u) << again.output;
    EXPECT_EQ(count(again.output, "rendered in"), 0u) << again.output;
    EXPECT_EQ(fs::last_write_time(cached), mtime);
    // The cached reference gives the same metrics as the freshly rendered one.
    const auto sweep2 = readJson(out / "sweep.json");
    ASSERT_EQ(sweep2["rows"].size(), 4u);
    for (std::size_t i = 0; i < 4; ++i)
        EXPECT_EQ(sweep2["rows"][i]["metrics"]["beauty.flip"],
                  sweep["rows"][i]["metrics"]["beauty.flip"])
            << i;

    // Another camera is another reference.
    const auto other = tt::runTwinrender("sweep " + SCENES +
                                         "planet.toml --set camera.width=48 --set camera.height=48"
                                         " --vary realtime.ssss.enabled=true --frames 1 --out " +
                                         out.string());
    ASSERT_EQ(other.exitCode, 0) << other.output;
    EXPECT_EQ(count(other.output, "rendered in"), 1u) << other.output;
}

TEST(Sweep, TheRaymarchersConvergenceAgainstATightRender) {
    const fs::path out = tt::freshDir("sweep_convergence");
    const auto r =
        tt::runTwinrender("sweep " + SCENES +
                          "planet.toml --set camera.width=48 --set camera.height=36"
                          " --vary raymarch.root_tolerance=0.05,1e-4 --vary raymarch.spp=1,4"
                          " --metric beauty.flip --out " +
                          out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const auto sweep = readJson(out / "sweep.json");
    EXPECT_EQ(sweep["test"], "raymarch");
    EXPECT_EQ(sweep["frames"], 1);
    EXPECT_NE(sweep["reference"].get<std::string>().find("spp 16"), std::string::npos)
        << sweep["reference"];
    ASSERT_EQ(sweep["rows"].size(), 4u);
    std::map<std::string, double> flip;  // "tolerance spp" -> beauty.flip
    for (const auto& row : sweep["rows"]) {
        EXPECT_TRUE(row["metrics"].contains("count.unbracketed_rays"));
        EXPECT_EQ(row["metrics"]["count.unbracketed_rays"].get<double>(), 0.0);
        EXPECT_TRUE(row["timings_ms"].contains("trace"));
        EXPECT_TRUE(fs::exists(out / row["dir"].get<std::string>() / "raymarch.png"));
        const auto& s = row["settings"];
        flip[s["raymarch.root_tolerance"].get<std::string>() + " " +
             s["raymarch.spp"].get<std::string>()] = row["metrics"]["beauty.flip"].get<double>();
    }
    // More samples per pixel come closer to the 16-sample render, at either root tolerance.
    // (The root itself is a Newton estimate inside a bracket no wider than the tolerance, so
    // the tolerance barely moves the image: the error of one sample dominates.)
    for (const std::string tol : {"0.05", "1e-4"}) {
        ASSERT_TRUE(flip.count(tol + " 1") && flip.count(tol + " 4")) << sweep["rows"];
        EXPECT_LT(flip[tol + " 4"], flip[tol + " 1"]) << tol;
    }
    EXPECT_EQ(tt::checkXml(readText(out / "sweep.svg")).error, "");
}

TEST(Sweep, BadInputIsExitFourBeforeAnyRender) {
    const fs::path out = tt::freshDir("sweep_bad");
    const std::string scene = SCENES + "planet.toml" + SMALL;
    const auto unknown = tt::runTwinrender(
        "sweep " + scene + " --vary realtime.ssss.nonsense=1,2 --out " + out.string());
    EXPECT_EQ(unknown.exitCode, 4) << unknown.output;
    EXPECT_NE(unknown.output.find("nonsense"), std::string::npos) << unknown.output;
    const auto badValue = tt::runTwinrender(
        "sweep " + scene + " --vary realtime.shadow_map.resolution=256,2 --out " + out.string());
    EXPECT_EQ(badValue.exitCode, 4) << badValue.output;
    EXPECT_NE(badValue.output.find("shadow_map.resolution"), std::string::npos) << badValue.output;
    const auto shard =
        tt::runTwinrender("sweep " + scene + GRID + " --shard 3/2 --out " + out.string());
    EXPECT_EQ(shard.exitCode, 4) << shard.output;
    EXPECT_NE(shard.output.find("--shard 3/2"), std::string::npos) << shard.output;
    const auto mixed = tt::runTwinrender("sweep " + scene +
                                         " --vary realtime.ssss.enabled=true,false"
                                         " --vary raymarch.spp=1,4 --out " +
                                         out.string());
    EXPECT_EQ(mixed.exitCode, 4) << mixed.output;
    const auto metric =
        tt::runTwinrender("sweep " + scene + GRID + " --metric beauty.nope --out " + out.string());
    EXPECT_EQ(metric.exitCode, 4) << metric.output;
    EXPECT_NE(metric.output.find("beauty.nope"), std::string::npos) << metric.output;
    const auto noVary = tt::runTwinrender("sweep " + scene + " --out " + out.string());
    EXPECT_EQ(noVary.exitCode, 4) << noVary.output;
    // Thresholds are read before the first render: an unknown metric, a missing file.
    const fs::path bounds = twinrender::testing::scratchFile("sweep_bad_thresholds.toml");
    tt::writeFile(bounds, "\"beauty.flip\" = { max = 0.1 }\n\"beauty.nope\" = { max = 1 }\n");
    const auto unknownMetric = tt::runTwinrender("sweep " + scene + GRID + " --thresholds " +
                                                 bounds.string() + " --out " + out.string());
    EXPECT_EQ(unknownMetric.exitCode, 4) << unknownMetric.output;
    EXPECT_NE(unknownMetric.output.find("sweep_bad_thresholds.toml:2:25: key 'beauty.nope.max': "
                                        "unknown metric 'beauty.nope'"),
              std::string::npos)
        << unknownMetric.output;
    EXPECT_EQ(count(unknownMetric.output, "rendered in"), 0u) << unknownMetric.output;
    const auto missing = tt::runTwinrender(
        "sweep " + scene + GRID + " --thresholds " +
        twinrender::testing::scratchFile("nowhere.toml").string() + " --out " + out.string());
    EXPECT_EQ(missing.exitCode, 4) << missing.output;
    EXPECT_NE(missing.output.find("thresholds file not found"), std::string::npos)
        << missing.output;
    EXPECT_EQ(tt::countFiles(out), 0u);
}

// At 64x48 with 1500 particles, ꟻLIP is about 0.096 with SSSS and 0.107 without, whatever
// the shadow map's resolution; SSSS off is also the faster. A bound of 0.1 passes the SSSS
// rows only, so the cheapest passing combination is not the cheapest one.
TEST(Sweep, ThresholdsMarkThePassingCombinationsAndNameTheCheapest) {
    const fs::path out = tt::freshDir("sweep_thresholds");
    const fs::path bounds = twinrender::testing::scratchFile("sweep_thresholds.toml");
    tt::writeFile(bounds,
                  "\"beauty.flip\" = { max = 0.1 }\n"
                  "[scenes.planet]\n"
                  "\"smoothness.ratio\" = { warn_max = 0.95 }\n");
    const auto r =
        tt::runTwinrender("sweep " + SCENES + "planet.toml" + SMALL + GRID + " --thresholds " +
                          bounds.string() + " --frames 1 --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const auto sweep = readJson(out / "sweep.json");
    ASSERT_EQ(sweep["rows"].size(), 4u);
    EXPECT_EQ(sweep["thresholds"], bounds.string());
    const nlohmann::json* cheapest = nullptr;
    for (const auto& row : sweep["rows"]) {
        const bool ssss = row["settings"]["realtime.ssss.enabled"] == "true";
        const double flip = row["metrics"]["beauty.flip"].get<double>();
        ASSERT_EQ(flip <= 0.1, ssss) << row;  // the premise of the bound
        EXPECT_EQ(row["status"], ssss ? "pass" : "fail") << row;
        EXPECT_EQ(row["failed"], ssss ? nlohmann::json::array() : nlohmann::json{"beauty.flip"});
        // The file's [scenes.planet] table applies too: the unsmoothed normals warn.
        EXPECT_EQ(row["warned"],
                  ssss ? nlohmann::json::array() : nlohmann::json{"smoothness.ratio"});
        const double ms = row["timings_ms"]["total"].get<double>();
        if (ssss && (!cheapest || ms < (*cheapest)["timings_ms"]["total"].get<double>()))
            cheapest = &row;
        // The combination's metrics.json holds its checks.
        const auto metrics = readJson(out / row["dir"].get<std::string>() / "metrics.json");
        EXPECT_EQ(metrics["status"], row["status"]) << metrics.dump(1);
    }
    ASSERT_NE(cheapest, nullptr);
    const std::string set =
        "--set realtime.ssss.enabled=true --set realtime.shadow_map.resolution=" +
        (*cheapest)["settings"]["realtime.shadow_map.resolution"].get<std::string>();
    const std::string line = lineStarting(r.output, "cheapest passing: ");
    EXPECT_EQ(line, fmt::format("cheapest passing: {:.2f} ms: {}",
                                (*cheapest)["timings_ms"]["total"].get<double>(), set))
        << r.output;
    EXPECT_NE(r.output.find(", fail (beauty.flip; warned: smoothness.ratio)"), std::string::npos)
        << r.output;

    // CSV: the verdict beside the settings (its columns: report/sweep_report_test.cpp).
    EXPECT_NE(readText(out / "sweep.csv").find("\n2,false,256,fail,beauty.flip,smoothness.ratio,"),
              std::string::npos);
    // The page: the verdict of every row, and the cheapest with its --set line.
    const std::string html = readText(out / "index.html");
    EXPECT_NE(html.find("Cheapest passing combination"), std::string::npos);
    EXPECT_NE(html.find("<code>" + set + "</code>"), std::string::npos);
    EXPECT_EQ(count(html, "<span class=\"badge pass\">pass</span>"), 2u + 1u);  // + header
    EXPECT_EQ(count(html, "<span class=\"badge fail\">fail</span>"), 2u);
    EXPECT_EQ(count(html, ">cheapest</span>"), 1u);

    // The line, given back to `run` with the sweep's own settings, passes the same bounds.
    const auto run =
        tt::runTwinrender("run " + SCENES + "planet.toml" + SMALL + " " + set + " --thresholds " +
                          bounds.string() + " --out " + (out / "run").string());
    EXPECT_EQ(run.exitCode, 0) << run.output;
    // While a combination that failed in the sweep fails there too.
    const auto failing =
        tt::runTwinrender("run " + SCENES + "planet.toml" + SMALL +
                          " --set realtime.ssss.enabled=false --thresholds " + bounds.string() +
                          " --out " + (out / "run_failing").string());
    EXPECT_EQ(failing.exitCode, 2) << failing.output;
}

TEST(Sweep, NoPassingCombinationIsExitTwoAndSaysWhichMetricFailed) {
    const fs::path out = tt::freshDir("sweep_none_pass");
    const fs::path bounds = twinrender::testing::scratchFile("sweep_none_pass.toml");
    tt::writeFile(bounds,
                  "\"beauty.flip\" = { max = 0.01 }\n"
                  "\"smoothness.ratio\" = { max = 0.95 }\n");
    const std::string sweep = "sweep " + SCENES + "planet.toml" + SMALL +
                              " --vary realtime.ssss.enabled=true,false --frames 1 --out " +
                              out.string() + " --thresholds ";
    const auto r = tt::runTwinrender(sweep + bounds.string());
    EXPECT_EQ(r.exitCode, 2) << r.output;
    // ꟻLIP fails in both, smoothness only without SSSS: the most frequent first.
    EXPECT_EQ(lineStarting(r.output, "no combination passes"),
              "no combination passes: beauty.flip failed in 2 of 2 combinations, "
              "smoothness.ratio failed in 1")
        << r.output;
    EXPECT_EQ(r.output.find("cheapest"), std::string::npos) << r.output;
    EXPECT_NE(readText(out / "index.html").find("No combination passes"), std::string::npos);

    // Past warning bounds only: the best verdict is a warning, and the cheapest such is named.
    tt::writeFile(bounds, "\"beauty.flip\" = { warn_max = 0.01 }\n");
    const auto warned = tt::runTwinrender(sweep + bounds.string());
    EXPECT_EQ(warned.exitCode, 1) << warned.output;
    EXPECT_NE(lineStarting(warned.output, "cheapest with warnings only: ").find("--set "),
              std::string::npos)
        << warned.output;
}

// A sequence scene: every frame of its range per combination, as `run` renders one. The churning
// ball of the flicker study, frames 0 to 2 at 64x48 without smoothing: the fixed impostor
// spheres flicker (measured temporal.flicker_mean 0.0119), the field radii follow the truth's
// own change (0.0030); a bound of 0.007 between them passes the field radii only.
TEST(Sweep, ASequenceRendersEveryFrameAndHoldsTheSummaryOverThem) {
    const fs::path out = tt::freshDir("sweep_sequence");
    const fs::path bounds = twinrender::testing::scratchFile("sweep_sequence.toml");
    tt::writeFile(bounds, "\"temporal.flicker_mean\" = { max = 0.007 }\n");
    const std::string sweep =
        "sweep " + SCENES +
        "studies/flicker.toml --set sequence.last=2 --set camera.width=64 "
        "--set camera.height=48 --set realtime.surface.method=none "
        "--vary realtime.particles.radius=fixed,field --metric temporal.flicker_mean";
    const auto r = tt::runTwinrender(sweep + " --frames 2 --thresholds " + bounds.string() +
                                     " --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // One reference per frame, shared by the combinations; --frames says it is not used.
    EXPECT_EQ(count(r.output, "rendered in"), 3u) << r.output;
    EXPECT_EQ(count(r.output, "cache hit"), 3u) << r.output;
    EXPECT_NE(r.output.find("note: --frames 2 is not used on a sequence scene"), std::string::npos)
        << r.output;
    EXPECT_TRUE(lineStarting(r.output, "cheapest passing: ")
                    .ends_with(" ms: --set realtime.particles.radius=field"))
        << r.output;

    const auto json = readJson(out / "sweep.json");
    EXPECT_EQ(json["sequence"], true);
    EXPECT_EQ(json["frames"], 3);
    ASSERT_EQ(json["rows"].size(), 2u);
    for (const auto& row : json["rows"]) {
        const bool fixed = row["settings"]["realtime.particles.radius"] == "fixed";
        const auto& m = row["metrics"];
        ASSERT_EQ(m["temporal.flicker_mean"].get<double>() > 0.007, fixed) << row;  // premise
        EXPECT_EQ(row["status"], fixed ? "fail" : "pass") << row;
        for (const char* k : {"temporal.flicker_max", "temporal.normal_flicker_mean_deg",
                              "temporal.normal_flicker_max_deg", "beauty.ssim"})
            EXPECT_TRUE(m[k].is_number()) << k;
        // The folder: the frame with the largest beauty.flip, and every frame's metrics.
        const auto metrics = readJson(out / row["dir"].get<std::string>() / "metrics.json");
        const auto& frames = metrics["sequence"]["frames"];
        ASSERT_EQ(frames.size(), 3u) << metrics.dump(1);
        EXPECT_FALSE(frames[0]["metrics"].contains("temporal.flicker"));
        double worst = -1.0, flicker = 0.0;
        std::int64_t worstFrame = -1;
        std::vector<double> times;
        for (const auto& f : frames) {
            const double flip = f["metrics"]["beauty.flip"].get<double>();
            if (flip > worst) {
                worst = flip;
                worstFrame = f["frame"].get<std::int64_t>();
            }
            if (f["metrics"].contains("temporal.flicker"))
                flicker += f["metrics"]["temporal.flicker"].get<double>() / 2.0;
            times.push_back(f["metrics"]["time.realtime_ms"].get<double>());
        }
        EXPECT_EQ(m["beauty.flip"].get<double>(), worst);
        EXPECT_EQ(metrics["sequence"]["shown_frame"], worstFrame);
        EXPECT_NEAR(m["temporal.flicker_mean"].get<double>(), flicker, 1e-12);
        // The time: the median frame's, each a new particle set.
        std::sort(times.begin(), times.end());
        EXPECT_EQ(row["timings_ms"]["total"].get<double>(), times[1]);
        EXPECT_TRUE(fs::exists(out / row["dir"].get<std::string>() / "realtime.png"));
    }
    EXPECT_NE(readText(out / "index.html").find("each a new particle set"), std::string::npos);

    // Shards merge into the same rows.
    const fs::path cache = out / "reference_cache";
    for (const char* k : {"1", "2"})
        ASSERT_EQ(tt::runTwinrender(sweep + " --shard " + k + "/2 --cache " + cache.string() +
                                    " --out " + (out / "shard" += k).string())
                      .exitCode,
                  0);
    ASSERT_EQ(tt::runTwinrender("merge " + (out / "shard1").string() + " " +
                                (out / "shard2").string() + " --out " + (out / "merged").string())
                  .exitCode,
              0);
    const auto merged = readJson(out / "merged" / "sweep.json");
    EXPECT_EQ(merged["sequence"], true);
    ASSERT_EQ(merged["rows"].size(), 2u);
    for (int i = 0; i < 2; ++i)  // the renders are deterministic; only the times differ
        EXPECT_EQ(merged["rows"][i]["metrics"]["temporal.flicker_mean"],
                  json["rows"][i]["metrics"]["temporal.flicker_mean"]);

    // A still scene has no flicker to sweep for: exit 4, nothing written.
    const fs::path still = tt::freshDir("sweep_sequence_still");
    const auto s = tt::runTwinrender("sweep " + SCENES + "planet.toml" + SMALL + GRID +
                                     " --metric temporal.flicker_mean --out " + still.string());
    EXPECT_EQ(s.exitCode, 4) << s.output;
    EXPECT_NE(s.output.find("--metric temporal.flicker_mean: a sequence's metric"),
              std::string::npos)
        << s.output;
    EXPECT_EQ(tt::countFiles(still), 0u);

    // Varied frames that change the number of frames: one report cannot hold them.
    const fs::path ranges = tt::freshDir("sweep_sequence_ranges");
    const auto v = tt::runTwinrender("sweep " + SCENES +
                                     "studies/flicker.toml --set camera.width=64 "
                                     "--set camera.height=48 --vary sequence.last=1,2 --out " +
                                     ranges.string());
    EXPECT_EQ(v.exitCode, 4) << v.output;
    EXPECT_NE(
        v.output.find("sweep: the combination sequence.last=2 gives 3 frames and the first 2"),
        std::string::npos)
        << v.output;
    EXPECT_EQ(tt::countFiles(ranges), 0u);
}

}  // namespace twinrender::e2e::sweep_test
