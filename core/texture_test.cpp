#include "core/texture.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace tc = twinrender::core;

namespace {
tc::Texture ramp() {
    // 4 x 2 texels: R = column index, G = row index (row 0 holds v = 1).
    tc::Image img(4, 2, {"R", "G", "B"});
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) {
            img.at(x, y, 0) = float(x);
            img.at(x, y, 1) = float(y);
        }
    return tc::Texture(img);
}
}  // namespace

TEST(Texture, SamplesLikeAGlSamplerRepeatInUClampInV) {
    const tc::Texture t = ramp();
    // Texel centres sit at (i + 0.5) / width.
    EXPECT_FLOAT_EQ(t.sample({0.125f, 0.75f}).x, 0.0f);
    EXPECT_FLOAT_EQ(t.sample({0.375f, 0.75f}).x, 1.0f);
    EXPECT_FLOAT_EQ(t.sample({0.25f, 0.75f}).x, 0.5f);  // halfway between columns 0 and 1
    // u wraps: between the last column (3) and the first (0).
    EXPECT_FLOAT_EQ(t.sample({0.0f, 0.75f}).x, 1.5f);
    EXPECT_FLOAT_EQ(t.sample({1.0f, 0.75f}).x, 1.5f);
    // v clamps: beyond the top texel centre the top row's value stays.
    EXPECT_FLOAT_EQ(t.sample({0.125f, 1.0f}).y, 0.0f);
    EXPECT_FLOAT_EQ(t.sample({0.125f, 0.0f}).y, 1.0f);
    EXPECT_FLOAT_EQ(t.sample({0.125f, 0.5f}).y, 0.5f);
}

TEST(Texture, ProceduralsAndConstants) {
    tc::TextureSource c;
    c.value = {0.1, 0.2, 0.3};
    const tc::Texture constant = tc::Texture::load(c);
    EXPECT_TRUE(constant.isConstant());
    EXPECT_FLOAT_EQ(constant.sample({0.7f, 0.2f}).z, 0.3f);
    tc::TextureSource grid;
    grid.kind = tc::TextureSource::Kind::Procedural;
    grid.procedural = "latlong_grid";
    const tc::Texture g = tc::Texture::load(grid);
    EXPECT_GT(g.sample({0.0005f, 0.4f}).x, 0.5f);  // the red seam meridian
    EXPECT_LT(g.sample({0.0005f, 0.4f}).y, 0.2f);
    EXPECT_LT(g.sample({0.25f, 0.5f}).x, 0.1f);  // 90 degrees east on the equator: a line
    EXPECT_GT(g.sample({0.27f, 0.4f}).x, 0.4f);  // between lines
    tc::TextureSource unknown;
    unknown.kind = tc::TextureSource::Kind::Procedural;
    unknown.procedural.assign("plasma");
    unknown.where.assign("scene.toml:4:1: key 'materials[0].diffuse'");
    try {
        tc::Texture::load(unknown);
        FAIL();
    } catch (const tc::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("materials[0].diffuse"), std::string::npos);
    }
}
