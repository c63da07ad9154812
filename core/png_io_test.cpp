#include "core/png_io.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image_io.h"
#include "core/oiio_module.h"

namespace tc = twinrender::core;
namespace fs = std::filesystem;

namespace {

constexpr int W = 23, H = 7;  // odd sizes: rows that do not fill whole bytes at 1-4 bits

// A PNG of any kind libpng writes, its samples from a fixed-seed LCG.
struct PngKind {
    std::string name;
    int colourType;
    int bitDepth;
    bool transparentColour = false;  // a tRNS chunk
    bool gamma = false;              // a gAMA chunk (1 / 2.2)
    bool interlaced = false;
};

fs::path writeKind(const PngKind& kind) {
    const fs::path path = fs::path(::testing::TempDir()) / ("png_io_" + kind.name + ".png");
    std::FILE* f = std::fopen(path.c_str(), "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, f);
    png_set_IHDR(png, info, W, H, kind.bitDepth, kind.colourType,
                 kind.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    std::uint32_t state = 77u;
    auto next = [&] { return (state = 1664525u * state + 1013904223u) >> 8; };
    if (kind.colourType == PNG_COLOR_TYPE_PALETTE) {
        std::vector<png_color> palette(1u << kind.bitDepth);
        for (auto& c : palette)
            c = {static_cast<png_byte>(next()), static_cast<png_byte>(next()),
                 static_cast<png_byte>(next())};
        png_set_PLTE(png, info, palette.data(), static_cast<int>(palette.size()));
        if (kind.transparentColour) {
            const png_byte alpha[3] = {0, 100, 255};  // entries 0-2; the rest opaque
            png_set_tRNS(png, info, alpha, 3, nullptr);
        }
    } else if (kind.transparentColour) {
        png_color_16 colour{};
        colour.gray = colour.red = colour.green = colour.blue = 1;
        png_set_tRNS(png, info, nullptr, 0, &colour);
    }
    if (kind.gamma) png_set_gAMA(png, info, 1.0 / 2.2);
    png_write_info(png, info);
    const int passes = png_set_interlace_handling(png);
    const std::size_t rowBytes = png_get_rowbytes(png, info);
    std::vector<png_byte> bytes(rowBytes * H);
    for (auto& b : bytes) b = static_cast<png_byte>(next());
    // Pixel value 1 somewhere, so that the transparent colour occurs in grey and RGB images.
    if (kind.bitDepth == 8) bytes[0] = bytes[1] = bytes[2] = 1;
    for (int pass = 0; pass < passes; ++pass)
        for (int y = 0; y < H; ++y) png_write_row(png, bytes.data() + y * rowBytes);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    return path;
}

const std::vector<PngKind>& kinds() {
    static const std::vector<PngKind> k = {
        {"rgb8", PNG_COLOR_TYPE_RGB, 8},
        {"rgba8", PNG_COLOR_TYPE_RGB_ALPHA, 8},
        {"rgb16", PNG_COLOR_TYPE_RGB, 16},
        {"rgba16", PNG_COLOR_TYPE_RGB_ALPHA, 16},
        {"grey1", PNG_COLOR_TYPE_GRAY, 1},
        {"grey2", PNG_COLOR_TYPE_GRAY, 2},
        {"grey4", PNG_COLOR_TYPE_GRAY, 4},
        {"grey8", PNG_COLOR_TYPE_GRAY, 8},
        {"grey16", PNG_COLOR_TYPE_GRAY, 16},
        {"grey_alpha8", PNG_COLOR_TYPE_GRAY_ALPHA, 8},
        {"grey_alpha16", PNG_COLOR_TYPE_GRAY_ALPHA, 16},
        {"palette4", PNG_COLOR_TYPE_PALETTE, 4},
        {"palette8", PNG_COLOR_TYPE_PALETTE, 8},
        {"palette_trns", PNG_COLOR_TYPE_PALETTE, 8, true},
        {"grey_trns", PNG_COLOR_TYPE_GRAY, 8, true},
        {"rgb_trns", PNG_COLOR_TYPE_RGB, 8, true},
        {"rgb_gamma", PNG_COLOR_TYPE_RGB, 8, false, true},
        {"rgb_interlaced", PNG_COLOR_TYPE_RGB, 8, false, false, true},
        {"rgba16_interlaced", PNG_COLOR_TYPE_RGB_ALPHA, 16, false, false, true},
    };
    return k;
}

}  // namespace

// Every kind of PNG reads through libpng to the values OpenImageIO gives, to the bit: the
// metrics of a PNG pair do not depend on which reader ran.
TEST(PngIo, ReadsEveryKindAsOpenImageIoDoes) {
    for (const PngKind& kind : kinds()) {
        const fs::path path = writeKind(kind);
        ASSERT_TRUE(tc::isPngFile(path)) << kind.name;
        const auto ours = tc::readPng(path);
        ASSERT_TRUE(ours) << kind.name;
        tc::DecodedPixels theirs;
        ASSERT_EQ(tc::oiio::api().read(path.string(), theirs), "") << kind.name;
        EXPECT_EQ(ours->width, theirs.width) << kind.name;
        EXPECT_EQ(ours->height, theirs.height) << kind.name;
        EXPECT_EQ(ours->channelNames.size(), theirs.channelNames.size()) << kind.name;
        EXPECT_FALSE(theirs.isFloat) << kind.name;
        ASSERT_EQ(ours->values.size(), theirs.values.size()) << kind.name;
        std::size_t differ = 0;
        for (std::size_t i = 0; i < ours->values.size(); ++i)
            differ += ours->values[i] != theirs.values[i];
        EXPECT_EQ(differ, 0u) << kind.name;
    }
}

// With alpha and a gAMA chunk, OpenImageIO premultiplies through the gamma: such a file is
// left to it, and readImage still reads it.
TEST(PngIo, AlphaWithGammaIsLeftToOpenImageIo) {
    const fs::path path = writeKind({"rgba_gamma", PNG_COLOR_TYPE_RGB_ALPHA, 8, false, true});
    EXPECT_FALSE(tc::readPng(path));
    const tc::Image image = tc::readImage(path);
    EXPECT_EQ(image.width(), W);
    EXPECT_EQ(image.channelNames(), (std::vector<std::string>{"R", "G", "B", "A"}));
}

TEST(PngIo, WrittenBytesReadBack) {
    std::vector<unsigned char> rgba(W * H * 4);
    for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = static_cast<unsigned char>(i * 37);
    for (std::size_t p = 0; p < rgba.size(); p += 4) rgba[p + 3] = 255;  // opaque: no premultiply
    const fs::path path = fs::path(::testing::TempDir()) / "png_io_written.png";
    tc::writePng(path, W, H, 4, rgba.data());
    const auto back = tc::readPng(path);
    ASSERT_TRUE(back);
    ASSERT_EQ(back->values.size(), rgba.size());
    for (std::size_t i = 0; i < rgba.size(); ++i)
        ASSERT_EQ(back->values[i], static_cast<float>(rgba[i]) * (1.0f / 255.0f)) << i;
}

TEST(PngIo, TruncatedFileNamesItself) {
    const fs::path whole = writeKind(kinds().front());
    const fs::path cut = fs::path(::testing::TempDir()) / "png_io_truncated.png";
    std::ifstream in(whole, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(cut, std::ios::binary).write(bytes.data(), bytes.size() / 2);
    try {
        tc::readImage(cut);
        FAIL() << "a truncated PNG was read";
    } catch (const tc::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("png_io_truncated.png"), std::string::npos)
            << e.what();
    }
}
