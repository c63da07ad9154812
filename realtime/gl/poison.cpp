#include "realtime/gl/poison.h"

#include <cstdlib>
#include <string_view>

namespace twinrender::realtime::gl {

bool poisonMode() {
    static const bool on = [] {
        const char* value = std::getenv("TWINRENDER_GL_POISON");
        return value != nullptr && *value != '\0' && std::string_view(value) != "0";
    }();
    return on;
}

}  // namespace twinrender::realtime::gl
