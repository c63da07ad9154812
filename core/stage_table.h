// Every stage a renderer times (a frame's timings_ms), in one table: its key, which renderer
// runs it, whether it runs every frame or once per particle set, and what it is. The table's
// order is the order a frame runs them; the reports, sweeps and studies list stages in it.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace twinrender::core {

enum class StageCadence {
    Frame,  // every frame
    Set,    // once per particle set (0 in a frame whose set's answers are kept)
    Setup,  // once per device and settings (not part of the frame's time)
};

struct StageInfo {
    std::string_view key;       // "gbuffer"
    std::string_view renderer;  // "realtime", "raymarch" or "both"
    StageCadence cadence;
    std::string_view meaning;
};

// Every stage, in the order a frame runs them ("total" first).
std::span<const StageInfo> stageTable();
// The stage with this key, or nullptr.
const StageInfo* findStage(std::string_view key);
// `stages` in the table's order, those it lacks after them by name.
std::vector<std::string> inStageOrder(std::vector<std::string> stages);

}  // namespace twinrender::core
