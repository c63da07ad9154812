// A one-line progress bar on standard error, shown only when it is a terminal.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace twinrender::app {

class Progress {
  public:
    explicit Progress(std::string label);
    ~Progress();
    // Thread-safe; redraws at most every 100 ms.
    void update(double fraction);
    void finish();

  private:
    std::string mLabel;
    bool mEnabled;
    std::mutex mMutex;
    std::chrono::steady_clock::time_point mLast;
    bool mDone = false;
};

}  // namespace twinrender::app
