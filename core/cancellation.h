// Stopping work early: a flag that something outside the work sets (app/'s Ctrl-C and
// SIGTERM handlers) and that the work loops poll, between tiles, passes, scenes and settings
// points.
#pragma once

#include <atomic>

namespace twinrender::core {

// Thrown where work stops because it was asked to. Not a std::exception on purpose: the
// handlers that turn one scene's or one combination's failure into a failed row (catching
// std::exception) let it through, up to app/'s main, which exits with 128 + the signal.
struct Cancelled {};

// Throws Cancelled when `flag` is set; a null flag never is.
inline void throwIfCancelled(const std::atomic<bool>* flag) {
    if (flag && flag->load(std::memory_order_relaxed)) throw Cancelled{};
}

}  // namespace twinrender::core
