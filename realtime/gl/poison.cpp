#include "realtime/gl/poison.h"

#include <cstdlib>
#include <string_view>

namespace twinrender::realtime::gl {

PoisonPattern poisonPattern() {
    static const PoisonPattern pattern = [] {
        const char* value = std::getenv("TWINRENDER_GL_POISON");
        if (value == nullptr || *value == '\0' || std::string_view(value) == "0")
            return PoisonPattern::Off;
        return std::string_view(value) == "finite" ? PoisonPattern::Finite : PoisonPattern::Nan;
    }();
    return pattern;
}

bool poisonMode() {
    return poisonPattern() != PoisonPattern::Off;
}

std::uint32_t poisonWord() {
    return poisonPattern() == PoisonPattern::Finite ? POISON_FINITE_WORD : POISON_NAN_WORD;
}

}  // namespace twinrender::realtime::gl
