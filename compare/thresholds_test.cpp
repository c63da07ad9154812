#include "compare/thresholds.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "tests/scratch_dir.h"

namespace twinrender::compare {
namespace {

// docs/design.md's example.
const char* EXAMPLE = R"("beauty.flip" = { max = 0.15, warn_max = 0.10 }
"shadow.iou" = { min = 0.90 }
[scenes.ringworld]
"shadow.iou" = { min = 0.80 }
)";

std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const core::InputError& e) {
        return e.what();
    }
    return "(no InputError)";
}

TEST(Thresholds, ParsesGlobalBoundsAndSceneOverrides) {
    const Thresholds t = Thresholds::parseString(EXAMPLE, "thresholds.toml");
    ASSERT_EQ(t.global().size(), 2u);
    const MetricBounds& flip = t.global().at("beauty.flip");
    ASSERT_TRUE(flip.max && flip.warnMax);
    EXPECT_DOUBLE_EQ(flip.max->value, 0.15);
    EXPECT_DOUBLE_EQ(flip.warnMax->value, 0.10);
    EXPECT_FALSE(flip.min || flip.warnMin);
    EXPECT_EQ(flip.max->where, "thresholds.toml:1:25");
    EXPECT_DOUBLE_EQ(t.global().at("shadow.iou").min->value, 0.90);
    ASSERT_EQ(t.scenes().count("ringworld"), 1u);
    EXPECT_DOUBLE_EQ(t.scenes().at("ringworld").at("shadow.iou").min->value, 0.80);
    EXPECT_EQ(t.scenes().at("ringworld").at("shadow.iou").min->where, "thresholds.toml:4:24");

    EXPECT_DOUBLE_EQ(t.forScene("ringworld").at("shadow.iou").min->value, 0.80);
    EXPECT_DOUBLE_EQ(t.forScene("planet").at("shadow.iou").min->value, 0.90);
    // The override replaces one bound; the others still come from the top level.
    EXPECT_DOUBLE_EQ(t.forScene("ringworld").at("beauty.flip").max->value, 0.15);
}

TEST(Thresholds, DottedKeysStandardTablesAndIntegersMeanTheSame) {
    const Thresholds t = Thresholds::parseString(R"(beauty.flip = { max = 0.15 }
["shadow.iou"]
min = 1
warn_min = 1
[scenes.planet.beauty]
psnr.min = 30
)",
                                                 "t.toml");
    EXPECT_DOUBLE_EQ(t.global().at("beauty.flip").max->value, 0.15);
    EXPECT_DOUBLE_EQ(t.global().at("shadow.iou").min->value, 1.0);
    EXPECT_DOUBLE_EQ(t.global().at("shadow.iou").warnMin->value, 1.0);
    EXPECT_DOUBLE_EQ(t.scenes().at("planet").at("beauty.psnr").min->value, 30.0);
}

TEST(Thresholds, PrecedenceIsFileGlobalThenSceneFileThenFileSceneTable) {
    const Thresholds t = Thresholds::parseString(R"("beauty.flip" = { max = 0.15, warn_max = 0.10 }
"shadow.iou" = { min = 0.90, warn_min = 0.95 }
"beauty.psnr" = { min = 25 }
[scenes.ringworld]
"shadow.iou" = { min = 0.80 }
)",
                                                 "thresholds.toml");
    core::ParameterTable scene("compare", "ringworld.toml");
    scene.set("thresholds.shadow.iou.min", 0.85, "ringworld.toml:20:1");
    scene.set("thresholds.beauty.flip.max", 0.2, "ringworld.toml:21:1");
    scene.set("other_setting", true, "ringworld.toml:22:1");

    const Bounds b = t.forScene("ringworld", &scene);
    // [scenes.ringworld] of the thresholds file beats the scene file ...
    EXPECT_DOUBLE_EQ(b.at("shadow.iou").min->value, 0.80);
    EXPECT_EQ(b.at("shadow.iou").min->where, "thresholds.toml:5:24");
    // ... which beats the thresholds file's top level, bound by bound.
    EXPECT_DOUBLE_EQ(b.at("beauty.flip").max->value, 0.2);
    EXPECT_EQ(b.at("beauty.flip").max->where, "ringworld.toml:21:1");
    EXPECT_DOUBLE_EQ(b.at("beauty.flip").warnMax->value, 0.10);
    EXPECT_DOUBLE_EQ(b.at("shadow.iou").warnMin->value, 0.95);
    EXPECT_DOUBLE_EQ(b.at("beauty.psnr").min->value, 25.0);

    // Another scene with the same scene-file table: no [scenes.NAME], so the scene file wins.
    EXPECT_DOUBLE_EQ(t.forScene("planet", &scene).at("shadow.iou").min->value, 0.85);

    // The thresholds keys were read; the scene's other keys were not.
    EXPECT_TRUE(scene.find("thresholds.shadow.iou.min")->read);
    EXPECT_FALSE(scene.entries().at("other_setting").read);
}

TEST(Thresholds, UnknownBoundNamesFileLineAndKey) {
    const std::string m = messageOf([] {
        Thresholds::parseString(
            "\"beauty.flip\" = { max = 0.15 }\n\n\"shadow.iou\" = { maxx = 0.9 }\n",
            "suite/thresholds.toml");
    });
    EXPECT_NE(m.find("suite/thresholds.toml:3:"), std::string::npos) << m;
    EXPECT_NE(m.find("shadow.iou.maxx"), std::string::npos) << m;
    EXPECT_NE(m.find("unknown bound 'maxx'"), std::string::npos) << m;
    EXPECT_NE(m.find("warn_max"), std::string::npos) << m;  // says what is allowed
}

TEST(Thresholds, UnknownMetricNamesFileLineKeyAndTheKnownMetrics) {
    const std::string m = messageOf([] {
        Thresholds::parseString(
            "\"beauty.flip\" = { max = 0.15 }\n\"beauty.flop\" = { max = 0.2 }\n",
            "suite/thresholds.toml");
    });
    EXPECT_NE(m.find("suite/thresholds.toml:2:"), std::string::npos) << m;
    EXPECT_NE(m.find("key 'beauty.flop.max'"), std::string::npos) << m;
    EXPECT_NE(m.find("unknown metric 'beauty.flop'"), std::string::npos) << m;
    EXPECT_NE(m.find("beauty.psnr, beauty.ssim, beauty.flip, "), std::string::npos) << m;
    EXPECT_NE(m.find("time.<renderer>_ms"), std::string::npos) << m;

    // In a scene's table of the file, and in a scene file's own [compare.thresholds].
    const std::string s = messageOf([] {
        Thresholds::parseString("[scenes.planet]\n\"shadow.iuo\" = { min = 0.9 }\n", "t.toml");
    });
    EXPECT_NE(s.find("t.toml:2:"), std::string::npos) << s;
    EXPECT_NE(s.find("scenes.planet.shadow.iuo.min"), std::string::npos) << s;
    EXPECT_NE(s.find("unknown metric 'shadow.iuo'"), std::string::npos) << s;
    core::ParameterTable scene("compare", "planet.toml");
    scene.set("thresholds.normal.mean.max", 3.0, "planet.toml:31:1");
    const std::string f = messageOf([&] { sceneFileBounds(scene); });
    EXPECT_NE(f.find("planet.toml:31:1"), std::string::npos) << f;
    EXPECT_NE(f.find("compare.thresholds.normal.mean.max"), std::string::npos) << f;
    EXPECT_NE(f.find("unknown metric 'normal.mean'"), std::string::npos) << f;

    // Families take any member.
    const Thresholds t =
        Thresholds::parseString("\"time.realtime_ms\" = { max = 500 }\n", "t.toml");
    EXPECT_TRUE(t.global().count("time.realtime_ms"));
}

TEST(Thresholds, NonNumericValuesNameFileLineAndKey) {
    std::string m = messageOf([] {
        Thresholds::parseString("# comment\n\"beauty.flip\" = { max = \"0.15\" }\n", "t.toml");
    });
    EXPECT_NE(m.find("t.toml:2:"), std::string::npos) << m;
    EXPECT_NE(m.find("beauty.flip.max"), std::string::npos) << m;
    EXPECT_NE(m.find("must be a number"), std::string::npos) << m;

    m = messageOf([] { Thresholds::parseString("\"beauty.flip\" = { max = true }\n", "t.toml"); });
    EXPECT_NE(m.find("must be a number"), std::string::npos) << m;
    m = messageOf([] { Thresholds::parseString("\"beauty.flip\" = { max = nan }\n", "t.toml"); });
    EXPECT_NE(m.find("finite"), std::string::npos) << m;
    // A bare value is a bound named after the metric's last part: the message shows the form.
    m = messageOf([] { Thresholds::parseString("\"beauty.flip\" = 0.15\n", "t.toml"); });
    EXPECT_NE(m.find("t.toml:1:"), std::string::npos) << m;
    EXPECT_NE(m.find("{ max = ..."), std::string::npos) << m;
    m = messageOf([] { Thresholds::parseString("max = 0.15\n", "t.toml"); });
    EXPECT_NE(m.find("without a metric"), std::string::npos) << m;
    m = messageOf([] { Thresholds::parseString("scenes = 3\n", "t.toml"); });
    EXPECT_NE(m.find("[scenes.NAME]"), std::string::npos) << m;
}

TEST(Thresholds, SyntaxErrorsAndMissingFilesAreInputErrors) {
    std::string m =
        messageOf([] { Thresholds::parseString("\"beauty.flip\" = { max = }\n", "t.toml"); });
    EXPECT_NE(m.find("t.toml:1:"), std::string::npos) << m;
    EXPECT_NE(m.find("syntax"), std::string::npos) << m;
    m = messageOf([] { Thresholds::parseFile("/nonexistent/thresholds.toml"); });
    EXPECT_NE(m.find("/nonexistent/thresholds.toml"), std::string::npos) << m;
}

TEST(Thresholds, WarnBoundBeyondItsFailBoundIsRejected) {
    const std::string m = messageOf([] {
        Thresholds::parseString("\"beauty.flip\" = { max = 0.1, warn_max = 0.2 }\n", "t.toml");
    });
    EXPECT_NE(m.find("t.toml:1:"), std::string::npos) << m;
    EXPECT_NE(m.find("warn_max"), std::string::npos) << m;
}

TEST(Thresholds, ParsesAFile) {
    const auto path = twinrender::testing::scratchFile("thresholds_test.toml");
    std::ofstream(path) << EXAMPLE;
    const Thresholds t = Thresholds::parseFile(path);
    EXPECT_EQ(t.file(), path.string());
    EXPECT_EQ(t.global().at("beauty.flip").max->where, path.string() + ":1:25");
    std::filesystem::remove(path);
}

TEST(Thresholds, SceneFileBadKeysNameTheirLocation) {
    core::ParameterTable scene("compare", "planet.toml");
    scene.set("thresholds.beauty.flip.maximum", 0.2, "planet.toml:31:1");
    std::string m = messageOf([&] { sceneFileBounds(scene); });
    EXPECT_NE(m.find("planet.toml:31:1"), std::string::npos) << m;
    EXPECT_NE(m.find("compare.thresholds.beauty.flip.maximum"), std::string::npos) << m;
    EXPECT_NE(m.find("unknown bound 'maximum'"), std::string::npos) << m;

    core::ParameterTable text("compare", "planet.toml");
    text.set("thresholds.beauty.flip.max", std::string("low"), "planet.toml:32:1");
    m = messageOf([&] { sceneFileBounds(text); });
    EXPECT_NE(m.find("planet.toml:32:1"), std::string::npos) << m;
    EXPECT_NE(m.find("must be a number"), std::string::npos) << m;

    core::ParameterTable integer("compare", "planet.toml");
    integer.set("thresholds.beauty.psnr.min", std::int64_t{30}, "planet.toml:33:1");
    EXPECT_DOUBLE_EQ(sceneFileBounds(integer).at("beauty.psnr").min->value, 30.0);
}

Bounds flipBounds() {
    return Thresholds::parseString(
               "\"beauty.flip\" = { max = 0.15, warn_max = 0.10 }\n"
               "\"shadow.iou\" = { min = 0.90, warn_min = 0.95 }\n",
               "t.toml")
        .global();
}

Status statusOf(const std::vector<Check>& checks) {
    return overallStatus(checks);
}

TEST(Evaluate, StatusesAtAndAroundTheBounds) {
    const Bounds b =
        filterBounds(flipBounds(), [](const std::string& m) { return m == "beauty.flip"; });
    auto at = [&](double v) { return statusOf(evaluate({{"beauty.flip", v}}, b)); };
    EXPECT_EQ(at(0.0), Status::Pass);
    EXPECT_EQ(at(0.10), Status::Pass);  // bounds are inclusive
    EXPECT_EQ(at(std::nextafter(0.10, 1.0)), Status::Warn);
    EXPECT_EQ(at(0.15), Status::Warn);
    EXPECT_EQ(at(std::nextafter(0.15, 1.0)), Status::Fail);
    EXPECT_EQ(at(1.0), Status::Fail);
    EXPECT_EQ(at(-std::numeric_limits<double>::infinity()), Status::Pass);

    const Bounds lower =
        filterBounds(flipBounds(), [](const std::string& m) { return m == "shadow.iou"; });
    auto iou = [&](double v) { return statusOf(evaluate({{"shadow.iou", v}}, lower)); };
    EXPECT_EQ(iou(1.0), Status::Pass);
    EXPECT_EQ(iou(0.95), Status::Pass);
    EXPECT_EQ(iou(std::nextafter(0.95, 0.0)), Status::Warn);
    EXPECT_EQ(iou(0.90), Status::Warn);
    EXPECT_EQ(iou(std::nextafter(0.90, 0.0)), Status::Fail);
}

TEST(Evaluate, OneCheckPerBoundInOrderWithReadableMessages) {
    const auto checks =
        evaluate({{"beauty.flip", 0.12}, {"shadow.iou", 0.5}, {"beauty.psnr", 30.0}}, flipBounds());
    ASSERT_EQ(checks.size(), 4u);  // psnr has no bounds: not checked
    EXPECT_EQ(checks[0].metric, "beauty.flip");
    EXPECT_EQ(checks[0].bound, "max");
    EXPECT_EQ(checks[0].status, Status::Pass);
    EXPECT_EQ(checks[1].bound, "warn_max");
    EXPECT_EQ(checks[1].status, Status::Warn);
    EXPECT_DOUBLE_EQ(checks[1].limit, 0.10);
    EXPECT_EQ(checks[1].message, "beauty.flip = 0.12 is above its warn_max 0.1 (t.toml:1:42)");
    EXPECT_EQ(checks[2].metric, "shadow.iou");
    EXPECT_EQ(checks[2].bound, "min");
    EXPECT_EQ(checks[2].status, Status::Fail);
    EXPECT_EQ(checks[2].message, "shadow.iou = 0.5 is below its min 0.9 (t.toml:2:24)");
    EXPECT_EQ(checks[3].bound, "warn_min");
    EXPECT_EQ(overallStatus(checks), Status::Fail);
    EXPECT_EQ(overallStatus({}), Status::Pass);
}

TEST(Evaluate, NanFailsAsNotComputable) {
    const auto checks =
        evaluate({{"beauty.flip", std::nan("")}, {"shadow.iou", 1.0}}, flipBounds());
    ASSERT_EQ(checks.size(), 4u);
    EXPECT_EQ(checks[0].status, Status::Fail);
    EXPECT_EQ(checks[1].status, Status::Fail);  // even the warn bound: the value is unknown
    EXPECT_NE(checks[0].message.find("not computable"), std::string::npos) << checks[0].message;
    EXPECT_TRUE(std::isnan(checks[0].value));
}

TEST(Evaluate, MissingMetricFails) {
    const auto checks = evaluate({{"beauty.flip", 0.01}}, flipBounds());
    ASSERT_EQ(checks.size(), 4u);
    EXPECT_EQ(checks[2].metric, "shadow.iou");
    EXPECT_EQ(checks[2].status, Status::Fail);
    EXPECT_NE(checks[2].message.find("shadow.iou was not computed"), std::string::npos)
        << checks[2].message;
    EXPECT_NE(checks[2].message.find("t.toml:2:"), std::string::npos) << checks[2].message;
    // Comparing plain images: keep only the beauty bounds, and nothing is missing.
    const Bounds beautyOnly =
        filterBounds(flipBounds(), [](const std::string& m) { return m.rfind("beauty.", 0) == 0; });
    EXPECT_EQ(overallStatus(evaluate({{"beauty.flip", 0.01}}, beautyOnly)), Status::Pass);
}

TEST(Evaluate, StatusNamesAndWorst) {
    EXPECT_EQ(toString(Status::Pass), "pass");
    EXPECT_EQ(toString(Status::Warn), "warn");
    EXPECT_EQ(toString(Status::Fail), "fail");
    EXPECT_EQ(worst(Status::Warn, Status::Pass), Status::Warn);
    EXPECT_EQ(worst(Status::Warn, Status::Fail), Status::Fail);
    EXPECT_EQ(formatValue(0.123456), "0.1235");
    EXPECT_EQ(formatValue(12345.6), "12346");
    EXPECT_EQ(formatValue(std::numeric_limits<double>::infinity()), "inf");
}

}  // namespace
}  // namespace twinrender::compare
