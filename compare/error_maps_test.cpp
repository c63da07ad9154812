#include "compare/error_maps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "compare/colour_map.h"
#include "compare/hdr_flip.h"
#include "compare/metrics.h"
#include "compare/testdata/synthetic_aov.h"
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

// The HDR-ꟻLIP map of an AOV pair is written beside ꟻLIP's, each pixel its per-pixel error
// through magma over [0, 1], as 8 bits.
TEST(ErrorMaps, HdrFlipMapIsTheMetricsErrorThroughMagma) {
    const fs::path dir = twinrender::testing::freshDir("error_maps_hdr");
    const core::Image ref = testdata::syntheticAov(32, 20, 16.0, 10.0, 8.0);
    const core::Image test = testdata::syntheticAov(32, 20, 17.0, 10.0, 8.5);
    const MetricResult result = computeMetrics(ref, test);
    const core::Image& map = result.errorMaps.at("beauty.hdrflip");
    EXPECT_EQ(map, hdrFlip(ref, test).errorMap);
    const auto images = writeErrorMapImages(result.errorMaps, dir);
    ASSERT_TRUE(images.count("beauty.hdrflip"));
    const ErrorMapImage& image = images.at("beauty.hdrflip");
    EXPECT_EQ(image.path, "error.beauty.hdrflip.png");
    EXPECT_EQ(image.label, "HDR-ꟻLIP error");
    EXPECT_EQ(images.at("beauty").path, "error.beauty.png");
    const core::Image png = core::readImage(dir / image.path);
    ASSERT_EQ(png.width(), map.width());
    ASSERT_EQ(png.height(), map.height());
    float largest = 0.0f;
    for (std::size_t p = 0; p < map.pixelCount(); ++p) {
        largest = std::max(largest, map.at(p, 0));
        float rgb[3];
        magma(map.at(p, 0), rgb);
        for (int c = 0; c < 3; ++c)  // 8 bits: rounded to the nearest of 255 steps
            ASSERT_EQ(png.at(p, c), std::floor(rgb[c] * 255.0f + 0.5f) * (1.0f / 255.0f))
                << "pixel " << p << " channel " << c;
    }
    EXPECT_GT(largest, 0.1f);  // the shifted sphere's edge: the map is not all dark
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
