#include "realtime/gl/timer_query.h"

#include <epoxy/gl.h>

namespace twinrender::realtime::gl {

namespace {
void deleteQuery(unsigned id) {
    glDeleteQueries(1, &id);
}
}  // namespace

TimerQuery::TimerQuery() {
    GLuint id = 0;
    glCreateQueries(GL_TIME_ELAPSED, 1, &id);
    mHandle = Handle(id, deleteQuery);
}

void TimerQuery::begin() const {
    glBeginQuery(GL_TIME_ELAPSED, mHandle.id());
}
void TimerQuery::end() const {
    glEndQuery(GL_TIME_ELAPSED);
}

double TimerQuery::milliseconds() const {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(mHandle.id(), GL_QUERY_RESULT, &ns);
    return static_cast<double>(ns) * 1e-6;
}

}  // namespace twinrender::realtime::gl
