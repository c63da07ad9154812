#include "app/interruption.h"

#include <csignal>

#include "core/cancellation.h"

namespace twinrender::app {

namespace {

std::atomic<bool> gInterrupted{false};
std::atomic<int> gSignal{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "a signal handler may only touch lock-free atomics");

extern "C" void onInterrupt(int signal) {
    if (gInterrupted.load()) {
        // The second signal: the default action (the process ends at once).
        std::signal(signal, SIG_DFL);
        std::raise(signal);
        return;
    }
    gSignal.store(signal);  // before the flag, which the work loops read first
    gInterrupted.store(true);
}

}  // namespace

void installInterruptHandlers() {
    struct sigaction action {};
    action.sa_handler = onInterrupt;
    // Each signal waits while the other's handler runs, so the second one finds the flag set.
    sigemptyset(&action.sa_mask);
    sigaddset(&action.sa_mask, SIGINT);
    sigaddset(&action.sa_mask, SIGTERM);
    // SA_RESTART: a read or write that the signal interrupts goes on; the work stops at its
    // next poll instead of failing an I/O call half-way.
    action.sa_flags = SA_RESTART;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

const std::atomic<bool>* interruptFlag() {
    return &gInterrupted;
}

int interruptSignal() {
    return gSignal.load();
}

void throwIfInterrupted() {
    core::throwIfCancelled(&gInterrupted);
}

}  // namespace twinrender::app
