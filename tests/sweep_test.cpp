// `twinrender sweep` end to end, on the planet scene at 64x48 so each sweep takes seconds:
// the rows of the cartesian product, the Pareto front and the chart, the reference cache, the
// raymarcher's convergence sweep, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "compare/svg_chart.h"
#include "compare/testdata/xml_check.h"
#include "tests/cli_harness.h"

namespace tt = twinrender::test;
using tt::readJson;
using tt::readText;
using tt::selftestInBrowser;
namespace tc = twinrender::compare;
namespace fs = std::filesystem;

namespace {

const std::string SCENES = std::string(TWINRENDER_SOURCE_DIR) + "/scenes/";
const std::string SMALL =
    " --set camera.width=64 --set camera.height=48 --set bodies.planet.particles=1500";
const std::string GRID =
    " --vary realtime.ssss.enabled=true,false --vary realtime.shadow_map.resolution=256,1024";

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
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
    EXPECT_EQ(tt::countFiles(out), 0u);
}
