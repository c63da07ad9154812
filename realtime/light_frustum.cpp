#include "realtime/light_frustum.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

namespace twinrender::realtime {

LightFrustum fitLightFrustum(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax,
                             const glm::dvec3& origin, const glm::dvec3& direction,
                             int resolution) {
    const glm::dvec3 forward = glm::normalize(direction);
    const glm::dvec3 helper =
        std::abs(forward.z) < 0.9 ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(1.0, 0.0, 0.0);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, helper));
    const glm::dvec3 up = glm::cross(right, forward);
    const glm::dvec3 centre = 0.5 * (boundsMin + boundsMax) - origin;

    // View: x = right, y = up, z = -forward, origin at the bounds' centre.
    glm::dmat4 view(1.0);
    for (int i = 0; i < 3; ++i) {
        view[i][0] = right[i];
        view[i][1] = up[i];
        view[i][2] = -forward[i];
    }
    view[3] =
        glm::dvec4(-glm::dot(right, centre), -glm::dot(up, centre), glm::dot(forward, centre), 1.0);

    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p((corner & 1) ? boundsMax.x : boundsMin.x,
                           (corner & 2) ? boundsMax.y : boundsMin.y,
                           (corner & 4) ? boundsMax.z : boundsMin.z);
        const glm::dvec3 l = glm::dvec3(view * glm::dvec4(p - origin, 1.0));
        lo = glm::min(lo, l);
        hi = glm::max(hi, l);
    }
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, 1e-30});
    LightFrustum f;
    f.view = view;
    // One texel of margin, so silhouettes at the bounds do not touch the border.
    const double margin = extent / std::max(resolution - 2, 1);
    f.texelSize = (extent + 2.0 * margin) / resolution;
    f.nearDepth = -hi.z - f.texelSize;
    f.farDepth = -lo.z + f.texelSize;
    f.clip = glm::ortho(lo.x - margin, hi.x + margin, lo.y - margin, hi.y + margin, f.nearDepth,
                        f.farDepth);
    return f;
}

}  // namespace twinrender::realtime
