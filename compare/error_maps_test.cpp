#include "compare/error_maps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "compare/metrics.h"
#include "compare/testdata/synthetic_report.h"
#include "core/image_io.h"
#include "tests/scratch_dir.h"

namespace twinrender::compare {
namespace {

namespace fs = std::filesystem;

TEST(ErrorMaps, WritesTheMetricsErrorMapsWithFixedRanges) {
    const fs::path dir = twinrender::testing::freshDir("error_maps");
    std::map<std::string, core::Image> maps;
    for (const char* key : {"beauty.flip", "normal", "other"}) {
        core::Image m(4, 2, {"e"});
        m.at(1, 0, 0) = 0.5f;
        maps[key] = m;
    }
    const auto images = writeErrorMapImages(maps, dir);
    ASSERT_EQ(images.size(), 3u);
    EXPECT_EQ(images.at("beauty").path, "error.beauty.png");
    EXPECT_EQ(images.at("beauty").label, "ꟻLIP error");
    EXPECT_DOUBLE_EQ(images.at("beauty").hi, 1.0);
    EXPECT_DOUBLE_EQ(images.at("normal").hi, 30.0);
    EXPECT_EQ(images.at("normal").unit, "°");
    EXPECT_EQ(images.at("other").label, "other error");
    EXPECT_DOUBLE_EQ(images.at("other").hi, 0.5);  // no style: its own maximum
    for (const auto& [buffer, m] : images) {
        const core::Image png = core::readImage(dir / m.path);
        EXPECT_EQ(png.width(), 4) << buffer;
    }
}

TEST(ErrorMaps, EveryMapOfTheMetricsHasAStyle) {
    const core::Image ref = testdata::syntheticAov(32, 20, 16.0, 10.0, 8.0);
    const core::Image test = testdata::syntheticAov(32, 20, 17.0, 10.0, 8.5);
    const auto& styles = errorMapStyles();
    for (const auto& [key, map] : computeMetrics(ref, test).errorMaps)
        EXPECT_TRUE(std::any_of(styles.begin(), styles.end(), [&](const ErrorMapStyle& s) {
            return s.key == key;
        })) << key;
}

}  // namespace
}  // namespace twinrender::compare
