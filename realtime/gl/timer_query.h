// GPU time of a span of commands (GL_TIME_ELAPSED). Queries cannot nest: passes are timed
// one after another.
#pragma once

#include "realtime/gl/handle.h"

namespace twinrender::realtime::gl {

class TimerQuery {
  public:
    TimerQuery();
    void begin() const;
    void end() const;
    // Waits for the result; milliseconds of GPU time between begin() and end().
    double milliseconds() const;

  private:
    Handle mHandle;
};

}  // namespace twinrender::realtime::gl
