#include "app/progress.h"

#include <unistd.h>

#include <cstdio>

namespace twinrender::app {

Progress::Progress(std::string label) : mLabel(std::move(label)), mEnabled(isatty(STDERR_FILENO)) {}

Progress::~Progress() {
    finish();
}

void Progress::update(double fraction) {
    if (!mEnabled) return;
    std::unique_lock lock(mMutex, std::try_to_lock);
    if (!lock.owns_lock() || mDone) return;
    const auto now = std::chrono::steady_clock::now();
    if (fraction < 1.0 && now - mLast < std::chrono::milliseconds(100)) return;
    mLast = now;
    constexpr int WIDTH = 30;
    const int filled = static_cast<int>(fraction * WIDTH + 0.5);
    std::string bar(filled, '#');
    bar.resize(WIDTH, '.');
    std::fprintf(stderr, "\r%-28s [%s] %3d%%", mLabel.c_str(), bar.c_str(),
                 static_cast<int>(fraction * 100.0 + 0.5));
    std::fflush(stderr);
}

void Progress::finish() {
    std::lock_guard lock(mMutex);
    if (mEnabled && !mDone) {
        std::fprintf(stderr, "\r%-70s\r", "");
        std::fflush(stderr);
    }
    mDone = true;
}

}  // namespace twinrender::app
