#include "core/stage_table.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

namespace twinrender::core {
namespace {

TEST(StageTable, KeysAreUniqueAndEveryRowSaysWhatItIs) {
    std::set<std::string_view> keys;
    for (const StageInfo& s : stageTable()) {
        EXPECT_TRUE(keys.insert(s.key).second) << s.key;
        EXPECT_TRUE(s.renderer == "realtime" || s.renderer == "raymarch" || s.renderer == "both")
            << s.key;
        EXPECT_FALSE(s.meaning.empty()) << s.key;
    }
    EXPECT_EQ(stageTable().front().key, "total");
    ASSERT_NE(findStage("gbuffer"), nullptr);
    EXPECT_EQ(findStage("gbuffer")->cadence, StageCadence::Frame);
    EXPECT_EQ(findStage("radius")->cadence, StageCadence::Set);
    EXPECT_EQ(findStage("no_such_stage"), nullptr);
}

TEST(StageTable, OrdersStagesAsAFrameRunsThemOthersAfterByName) {
    EXPECT_EQ(inStageOrder({"zeta", "shade", "trace", "total", "alpha", "gbuffer", "upload"}),
              (std::vector<std::string>{"total", "upload", "gbuffer", "shade", "trace", "alpha",
                                        "zeta"}));
}

}  // namespace
}  // namespace twinrender::core
