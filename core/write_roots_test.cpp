#include "core/write_roots.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "core/image_io.h"
#include "tests/scratch_dir.h"

namespace tc = twinrender::core;
namespace fs = std::filesystem;

namespace {

// Registers folders for one test and forgets them after it, whatever it throws.
struct Confined {
    explicit Confined(const fs::path& dir) { tc::allowWritesUnder(dir); }
    ~Confined() { tc::clearWriteRoots(); }
};

}  // namespace

TEST(WriteRoots, InsideIsDecidedAfterDotsAndLinksAreResolved) {
    const fs::path dir = twinrender::testing::freshDir("write_roots_inside");
    fs::create_directories(dir / "out");
    fs::create_directories(dir / "elsewhere");
    fs::create_directory_symlink(dir / "elsewhere", dir / "out" / "link");
    EXPECT_TRUE(tc::isInside(dir / "out", dir / "out"));
    EXPECT_TRUE(tc::isInside(dir / "out", dir / "out" / "a" / "b.exr"));
    EXPECT_TRUE(tc::isInside(dir / "out/", dir / "out" / "a" / ".." / "b"));
    EXPECT_FALSE(tc::isInside(dir / "out", dir / "out" / ".." / "escaped"));
    EXPECT_FALSE(tc::isInside(dir / "out", dir / "out" / "a" / ".." / ".." / "escaped"));
    EXPECT_FALSE(tc::isInside(dir / "out", dir / "outer"));  // a prefix of the name only
    EXPECT_FALSE(tc::isInside(dir / "out", dir / "out" / "link" / "x"));  // a link leads out
    EXPECT_THROW(tc::requireInside(dir / "out", dir / "elsewhere", "m.json"), tc::InputError);
}

TEST(WriteRoots, NothingIsWrittenOutsideTheRegisteredFolders) {
    const fs::path dir = twinrender::testing::freshDir("write_roots_confined");
    const Confined confined(dir / "out");
    tc::writeTextFile(dir / "out" / "scene" / "a.json", "{}");
    EXPECT_TRUE(fs::exists(dir / "out" / "scene" / "a.json"));
    try {
        tc::writeTextFile(dir / "out" / ".." / "escaped" / "a.json", "{}");
        FAIL() << "a write outside the output folder went through";
    } catch (const tc::OutputError& e) {
        EXPECT_NE(std::string(e.what()).find("refusing to write outside"), std::string::npos);
    }
    EXPECT_THROW(tc::makeFolders(dir / "escaped2"), tc::OutputError);
    EXPECT_FALSE(fs::exists(dir / "escaped"));
    EXPECT_FALSE(fs::exists(dir / "escaped2"));
    // A file the user named is a place of its own (--junit FILE).
    tc::allowWritesUnder(dir / "junit.xml");
    tc::writeTextFile(dir / "junit.xml", "<x/>");
    EXPECT_TRUE(fs::exists(dir / "junit.xml"));
    EXPECT_THROW(tc::writeTextFile(dir / "junit.xml.2", "<x/>"), tc::OutputError);
}
