#include "report/buffer_display.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/frame.h"
#include "core/image_io.h"
#include "report/testdata/synthetic_report.h"
#include "tests/scratch_dir.h"

namespace twinrender::report {
namespace {

using namespace twinrender::compare;  // what the report shows

namespace fs = std::filesystem;

TEST(BufferImages, VisualisationsFollowTheirConventions) {
    core::Image aov = core::aov::makeImage(4, 1);
    auto set = [&](int x, const char* ch, float v) { aov.at(x, 0, aov.channelIndex(ch)) = v; };
    for (int x = 0; x < 3; ++x) set(x, "A", 1.0f);
    set(0, "N.Z", 1.0f);
    set(0, "Z", 1.0f);
    set(1, "Z", 10.0f);
    set(2, "Z", 100.0f);
    set(0, "uv.U", 0.25f);
    set(0, "uv.V", 0.75f);
    set(0, "id", 0.0f);
    set(1, "id", 1.0f);
    set(2, "id", 0.0f);
    set(0, "shadow", 1.0f);

    const core::Image n = visualiseBuffer(aov, "normal");
    EXPECT_FLOAT_EQ(n.at(0, 0, 0), 0.5f);
    EXPECT_FLOAT_EQ(n.at(0, 0, 1), 0.5f);
    EXPECT_FLOAT_EQ(n.at(0, 0, 2), 1.0f);
    const core::Image uv = visualiseBuffer(aov, "uv");
    EXPECT_FLOAT_EQ(uv.at(0, 0, 0), 0.25f);
    EXPECT_FLOAT_EQ(uv.at(0, 0, 1), 0.75f);
    EXPECT_FLOAT_EQ(uv.at(0, 0, 2), 0.0f);
    // Depth: log-scaled, near white, far grey; 10 is halfway between 1 and 100.
    const core::Image d = visualiseBuffer(aov, "depth");
    EXPECT_FLOAT_EQ(d.at(0, 0, 0), 1.0f);
    EXPECT_NEAR(d.at(1, 0, 0), 1.0f - 0.375f, 1e-6);
    EXPECT_FLOAT_EQ(d.at(2, 0, 0), 0.25f);
    // A shared range shifts the mapping.
    BufferVisualSettings wide;
    wide.depthRange = {0.1, 1000.0};
    EXPECT_LT(visualiseBuffer(aov, "depth", wide).at(0, 0, 0), 1.0f);
    // Ids: one colour per body, the same wherever it appears; background differs from all.
    const core::Image id = visualiseBuffer(aov, "id");
    EXPECT_EQ(id.at(0, 0, 0), id.at(2, 0, 0));
    float diff = 0.0f;
    for (int c = 0; c < 3; ++c) diff += std::abs(id.at(0, 0, c) - id.at(1, 0, c));
    EXPECT_GT(diff, 0.3f);
    const core::Image sh = visualiseBuffer(aov, "shadow");
    EXPECT_FLOAT_EQ(sh.at(0, 0, 0), 1.0f);
    EXPECT_FLOAT_EQ(sh.at(1, 0, 0), 0.3f);
    // No coverage: the same slate background in every buffer but beauty.
    for (const char* b : {"normal", "uv", "depth", "id", "shadow", "emission"})
        EXPECT_NEAR(visualiseBuffer(aov, b).at(3, 0, 0), 0.10f, 1e-6) << b;

    core::Image rgbOnly(2, 2, {"R", "G", "B"});
    EXPECT_THROW(visualiseBuffer(rgbOnly, "normal"), core::NotComparableError);
    EXPECT_THROW(visualiseBuffer(aov, "albedo"), std::invalid_argument);
}

TEST(BufferImages, WritesOnePngPerAvailableBuffer) {
    const fs::path dir = twinrender::testing::freshDir("buffer_display");
    core::Image aov = testdata::syntheticAov(16, 12, 8.0, 6.0, 5.0);
    // Without light from emitting surfaces nor an atmosphere, every buffer but the irradiance
    // and the in-scatter.
    core::Image dark = aov;
    for (const char* c : {"irradiance.R", "irradiance.G", "irradiance.B", "inscatter.R",
                          "inscatter.G", "inscatter.B"})
        for (std::size_t p = 0; p < dark.pixelCount(); ++p) dark.at(p, dark.channelIndex(c)) = 0.0f;
    EXPECT_EQ(writeBufferImages(dark, nullptr, dir, "dark").size(), bufferNames().size() - 2);
    const auto files = writeBufferImages(aov, nullptr, dir, "realtime");
    ASSERT_EQ(files.size(), bufferNames().size());
    for (const auto& [buffer, name] : files) {
        EXPECT_EQ(name, "realtime." + buffer + ".png");
        const core::Image png = core::readImage(dir / name);
        EXPECT_EQ(png.width(), 16);
        EXPECT_EQ(png.height(), 12);
    }
    core::Image beautyOnly(16, 12, {"R", "G", "B"});
    EXPECT_EQ(writeBufferImages(beautyOnly, nullptr, dir, "plain").size(), 1u);
}

}  // namespace
}  // namespace twinrender::report
