#include "realtime/octahedral.h"

#include <cmath>
#include <glm/geometric.hpp>

namespace twinrender::realtime {

namespace {
glm::vec2 signNotZero(glm::vec2 v) {
    return {v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f};
}
}  // namespace

glm::vec2 octEncode(glm::vec3 n) {
    const glm::vec2 p = glm::vec2(n.x, n.y) / (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));
    if (n.z >= 0.0f) return p;
    return (1.0f - glm::abs(glm::vec2(p.y, p.x))) * signNotZero(p);
}

glm::vec3 octDecode(glm::vec2 e) {
    glm::vec3 n(e.x, e.y, 1.0f - std::abs(e.x) - std::abs(e.y));
    if (n.z < 0.0f) {
        const glm::vec2 xy =
            (1.0f - glm::abs(glm::vec2(n.y, n.x))) * signNotZero(glm::vec2(n.x, n.y));
        n.x = xy.x;
        n.y = xy.y;
    }
    return glm::normalize(n);
}

}  // namespace twinrender::realtime
