#include "core/image_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/frame.h"

namespace tc = twinrender::core;
namespace fs = std::filesystem;

TEST(ImageIo, ExrKeepsChannelNamesAndFloatValues) {
    tc::Image img = tc::aov::makeImage(5, 3);
    img.at(1, 2, img.channelIndex("N.Y")) = -0.25f;
    img.at(4, 0, img.channelIndex("Z")) = 1e10f;
    img.at(0, 0, img.channelIndex("R")) = 123.5f;  // HDR, not clamped
    const fs::path p = fs::path(::testing::TempDir()) / "aov.exr";
    tc::writeImage(img, p);
    const tc::Image back = tc::readImage(p);
    ASSERT_EQ(back.width(), 5);
    ASSERT_EQ(back.height(), 3);
    for (const auto& name : tc::aov::channelNames()) {
        const int a = img.channelIndex(name), b = back.channelIndex(name);
        ASSERT_GE(b, 0) << name;
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 5; ++x) {
                const float u = img.at(x, y, a), v = back.at(x, y, b);
                if (std::isinf(u))
                    EXPECT_TRUE(std::isinf(v));
                else
                    EXPECT_EQ(u, v) << name << " " << x << "," << y;
            }
    }
    EXPECT_EQ(back.at(1, 2, back.channelIndex("N.Y")), -0.25f);
    EXPECT_EQ(back.at(0, 0, back.channelIndex("id")), -1.0f);  // background id
}

TEST(ImageIo, PngIsEightBitClampedAndTopRowFirst) {
    tc::Image img(2, 2, {"R", "G", "B"});
    img.at(0, 0, 0) = 1.0f;  // top-left red
    img.at(1, 1, 2) = 2.0f;  // clamped to 1
    img.at(1, 0, 1) = 0.5f;  // 127.5 -> 128
    const fs::path p = fs::path(::testing::TempDir()) / "small.png";
    tc::writeImage(img, p);
    const tc::Image back = tc::readImage(p);
    EXPECT_EQ(back.at(0, 0, back.channelIndex("R")), 1.0f);
    EXPECT_EQ(back.at(1, 1, back.channelIndex("B")), 1.0f);
    EXPECT_NEAR(back.at(1, 0, back.channelIndex("G")), 128.0f / 255.0f, 1e-6f);
    EXPECT_EQ(back.at(0, 1, back.channelIndex("R")), 0.0f);
}

TEST(ImageIo, FailedWritesLeaveNothingAndUnreadableFilesNameThemselves) {
    const fs::path dir = fs::path(::testing::TempDir()) / "atomic";
    fs::remove_all(dir);
    EXPECT_THROW(tc::writeFileAtomically(dir / "out.json",
                                         [](const fs::path& tmp) {
                                             tc::writeTextFile(tmp, "partial");
                                             throw std::runtime_error("interrupted");
                                         }),
                 std::runtime_error);
    std::size_t files = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir)) files += e.is_regular_file();
    EXPECT_EQ(files, 0u);
    try {
        tc::readImage(dir / "missing.exr");
        FAIL();
    } catch (const tc::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("missing.exr"), std::string::npos);
    }
    // A device never ends: /dev/zero is refused before a byte is read (it once kept
    // `compare` reading for ever), and so is a folder.
    for (const fs::path& notAFile : {fs::path("/dev/zero"), dir}) {
        try {
            tc::readImage(notAFile);
            FAIL() << notAFile;
        } catch (const tc::InputError& e) {
            EXPECT_NE(std::string(e.what()).find(notAFile.string() + ": not an image file"),
                      std::string::npos)
                << e.what();
        }
    }
}

// A damaged EXR header whose attribute claims 2 GB (OpenEXR would allocate it before reading)
// and an image beyond the largest side are rejected naming the file, before any allocation.
TEST(ImageIo, DamagedHeadersAreRejectedBeforeAllocating) {
    const fs::path p = fs::path(::testing::TempDir()) / "damaged.exr";
    {
        std::string bytes("\x76\x2f\x31\x01\x02\x00\x00\x00", 8);
        bytes += std::string("comments\0string\0", 16) + std::string("\x00\x00\x00\x7f", 4);
        bytes += "text";
        std::ofstream(p, std::ios::binary) << bytes;
    }
    try {
        tc::readImage(p);
        ADD_FAILURE() << "no error";
    } catch (const tc::InputError& e) {
        EXPECT_NE(std::string(e.what()).find(p.string() + ": not a valid OpenEXR file: header "
                                                          "attribute 'comments' (string) claims "
                                                          "2130706432 bytes"),
                  std::string::npos)
            << e.what();
    }
    const fs::path wide = fs::path(::testing::TempDir()) / "wide.exr";
    tc::writeImage(tc::Image(16385, 1, {"R"}), wide);
    EXPECT_THROW(tc::readImage(wide), tc::InputError);
}
