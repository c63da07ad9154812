// Ctrl-C (SIGINT) and SIGTERM. The handlers only set a flag (async-signal-safe); the work
// loops poll it (core::RenderInput::cancel in the raymarcher's tiles and between the real-time
// passes, and render() before and after each render), and the command unwinds with
// core::Cancelled: no report is written, temporary files are removed as every write removes
// its own on an exception, and main exits with 128 + the signal (130, 143). A second signal
// ends the process at once, as the default action would.
//
// The flag is the process's one mutable global (CONTRIBUTING.md, "House style"): a signal handler
// can reach no other state.
#pragma once

#include <atomic>

namespace twinrender::app {

// Installs the handlers for SIGINT and SIGTERM.
void installInterruptHandlers();

// The flag the handlers set, for core::RenderInput::cancel.
const std::atomic<bool>* interruptFlag();

// The signal that interrupted the command, or 0.
int interruptSignal();

// Throws core::Cancelled when a signal has arrived.
void throwIfInterrupted();

}  // namespace twinrender::app
