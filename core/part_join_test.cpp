// Joining the parts of a frame: each part's rows, its counters as one render counts them, and
// the refusal of parts that do not belong together.
#include "core/part_join.h"

#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "core/shading.h"

namespace tr = twinrender;
using tr::core::Frame;
using tr::core::PartJoin;

namespace {

// A frame 5 x 10 pixels in tiles of 2 (five rows of tiles): part 1 of 2 holds rows 0, 2 and 4,
// part 2 rows 1 and 3, each in an image of its rows of pixels alone. The frame's pixel in the
// row of tiles r holds 10 * r + channel.
Frame part(int index, int count = 2) {
    Frame f;
    f.renderer = "raymarch";
    f.device = index == 1 ? "cpu A" : "cpu B";
    f.settings = {{"spp", 4}};
    f.particleCount = 12;
    tr::core::PartRecord r;
    r.part = {.index = index, .count = count};
    r.tileSize = 2;
    r.height = 10;
    f.image = tr::core::Image(5, r.heightHeld(), {"R", "G", "B", "Z"});
    for (int row = 0; row < f.image.height(); ++row)
        for (int x = 0; x < 5; ++x)
            for (int c = 0; c < 4; ++c)
                f.image.at(x, row, c) = 10.0f * (r.part.frameRow(row, 2) / 2) + c;
    // Sums whose order matters: in row order 1e16 + 1 - 1e16 + 1 + 0.5 is 1.5, in part order
    // (1e16 - 1e16 + 0.5) + (1 + 1) is 2.5.
    r.means["error"] = index == 1 ? tr::core::PartMean{.rowSums = {1e16, -1e16, 0.5}, .samples = 3}
                                  : tr::core::PartMean{.rowSums = {1.0, 1.0}, .samples = 5};
    r.shared = {"bodies"};
    r.maxima = {"error_max"};
    f.counters = {{"rays", index == 1 ? 300.0 : 40.0},
                  {"bodies", 2.0},
                  {"error", 0.0},
                  {"error_max", index == 1 ? 0.25 : 0.75}};
    f.timingsMs = {{"build", 1.0}, {"total", index == 1 ? 10.0 : 6.0}};
    f.part = r;
    return f;
}

std::string refusal(PartJoin& join, Frame f, const std::string& where) {
    try {
        join.add(std::move(f), where);
    } catch (const tr::core::InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(PartJoin, KeepsEachPartsRowsAndCountsAsOneRender) {
    PartJoin join;
    join.add(part(2), "b.json");
    join.add(part(1), "a.json");
    const Frame whole = join.frame(1.0f);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 5; ++x)
            for (int c = 0; c < 4; ++c)
                ASSERT_EQ(whole.image.at(x, y, c), 10.0f * (y / 2) + c) << x << "," << y;
    EXPECT_EQ(whole.counters.at("rays"), 340.0);
    EXPECT_EQ(whole.counters.at("bodies"), 2.0);
    EXPECT_EQ(whole.counters.at("error"), 1.5 / 8.0);
    EXPECT_EQ(whole.counters.at("error_max"), 0.75);
    EXPECT_EQ(whole.timingsMs.at("total"), 16.0);
    EXPECT_EQ(whole.timingsMs.at("build"), 2.0);
    EXPECT_EQ(whole.device, "cpu A; cpu B");
    EXPECT_FALSE(whole.part);
    EXPECT_EQ(whole.particleCount, 12u);
    const glm::vec3 shown = tr::core::tonemap({30.0f, 31.0f, 32.0f}, 1.0f);
    EXPECT_EQ(whole.display.at(0, 7, 2), shown.z);
    ASSERT_EQ(join.parts().size(), 2u);
    EXPECT_EQ(join.parts()[1]["device"], "cpu B");
    EXPECT_EQ(join.parts()[1]["timings_ms"]["total"], 6.0);
}

TEST(PartJoin, RefusesPartsThatDoNotBelongTogether) {
    PartJoin join;
    join.add(part(1), "a.json");
    EXPECT_NE(refusal(join, part(1), "again.json").find("both part 1/2"), std::string::npos);
    EXPECT_NE(refusal(join, part(2, 3), "c.json").find("split into 3 and 2 parts"),
              std::string::npos);
    Frame wider = part(2);
    wider.image = tr::core::Image(6, 4, {"R", "G", "B", "Z"});
    EXPECT_NE(refusal(join, wider, "w.json").find("6x10"), std::string::npos);
    Frame higher = part(2);
    higher.image = tr::core::Image(5, 10, {"R", "G", "B", "Z"});
    EXPECT_NE(refusal(join, higher, "h.json").find("an image 10 pixels high"), std::string::npos);
    Frame other = part(2);
    other.settings = {{"spp", 16}};
    EXPECT_NE(refusal(join, other, "s.json").find("spp 16 against 4"), std::string::npos);
    Frame bodies = part(2);
    bodies.counters["bodies"] = 3.0;
    EXPECT_NE(refusal(join, bodies, "n.json").find("bodies is 3 and 2"), std::string::npos);
    Frame rows = part(2);
    rows.part->means["error"].rowSums.push_back(0.0);
    EXPECT_NE(refusal(join, rows, "r.json").find("has 3 row sums"), std::string::npos);
    Frame whole = part(2);
    whole.part.reset();
    EXPECT_NE(refusal(join, whole, "x.json").find("a whole frame"), std::string::npos);
    // None of them was taken: part 2 is still missing.
    try {
        join.frame(1.0f);
        ADD_FAILURE() << "a frame without part 2";
    } catch (const tr::core::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("part 2/2 is missing"), std::string::npos) << e.what();
    }
}

TEST(PartJoin, TheRecordReadsBackAndADamagedOneIsNamed) {
    const tr::core::PartRecord r = *part(1).part;
    const tr::core::PartRecord back = tr::core::partRecordFromJson(toJson(r), "p.json");
    EXPECT_EQ(back.part.index, 1);
    EXPECT_EQ(back.part.count, 2);
    EXPECT_EQ(back.tileSize, 2);
    EXPECT_EQ(back.height, 10);
    EXPECT_EQ(back.means.at("error").rowSums, r.means.at("error").rowSums);
    EXPECT_EQ(back.means.at("error").samples, 3);
    EXPECT_EQ(back.shared, r.shared);
    EXPECT_EQ(back.maxima, r.maxima);
    nlohmann::json damaged = toJson(r);
    damaged["part"] = 3;
    try {
        tr::core::partRecordFromJson(damaged, "p.json");
        ADD_FAILURE() << "part 3 of 2 read";
    } catch (const tr::core::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("p.json: \"tile\".part is 3"), std::string::npos)
            << e.what();
    }
}

TEST(PartJoin, APartHoldsItsRowsOfPixelsAloneTheLastOneCutByTheFrame) {
    // 10 pixels high in tiles of 4: rows of tiles 0 (pixels 0-3), 1 (4-7) and 2 (8-9).
    const tr::core::FramePart first{.index = 1, .count = 2}, second{.index = 2, .count = 2};
    EXPECT_EQ(first.heightHeld(10, 4), 6);
    EXPECT_EQ(second.heightHeld(10, 4), 4);
    EXPECT_EQ(first.frameRow(3, 4), 3);
    EXPECT_EQ(first.frameRow(4, 4), 8);
    EXPECT_EQ(first.frameRow(5, 4), 9);
    EXPECT_EQ(second.frameRow(0, 4), 4);
    for (int row = 0; row < 6; ++row) EXPECT_EQ(first.imageRow(first.frameRow(row, 4), 4), row);
    for (int row = 0; row < 4; ++row) EXPECT_EQ(second.imageRow(second.frameRow(row, 4), 4), row);
    // A whole frame is its own part.
    EXPECT_EQ(tr::core::FramePart{}.heightHeld(10, 4), 10);
    EXPECT_EQ(tr::core::FramePart{}.imageRow(9, 4), 9);
}
