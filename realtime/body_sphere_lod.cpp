#include "realtime/body_sphere_lod.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

namespace twinrender::realtime {

double projectedRadiusPixels(const core::Camera& camera, const glm::dvec3& centre, double radius) {
    const double d = glm::length(centre - camera.position());
    if (camera.eyeDepth(centre) <= 0.0 || d <= radius)
        return std::numeric_limits<double>::infinity();
    const double f = 0.5 * camera.height() / camera.tanHalfFovY();
    return f * radius / std::sqrt((d - radius) * (d + radius));
}

BodySphereChoice chooseBodySpheres(std::span<const core::BodySphere> spheres, std::size_t bodyCount,
                                   const core::Camera& camera, double pixels) {
    BodySphereChoice out;
    out.replaced.assign(bodyCount, false);
    if (pixels <= 0.0) return out;
    for (const core::BodySphere& s : spheres)
        if (s.radius > 0.0 && projectedRadiusPixels(camera, s.centre, s.radius) < pixels) {
            out.drawn.push_back(s);
            out.replaced[s.body] = true;
        }
    for (const core::BodySphere& a : out.drawn)
        for (const core::BodySphere& b : spheres)
            if (!out.replaced[b.body] && glm::length(a.centre - b.centre) < a.reach + b.reach)
                out.touchesOthers = true;
    return out;
}

std::vector<std::uint32_t> withoutReplaced(std::span<const std::uint32_t> indices,
                                           std::span<const std::uint32_t> body,
                                           const std::vector<bool>& replaced) {
    std::vector<std::uint32_t> out;
    auto keep = [&](std::uint32_t i) {
        if (!replaced[body[i]]) out.push_back(i);
    };
    if (indices.empty())
        for (std::uint32_t i = 0; i < body.size(); ++i) keep(i);
    else
        for (std::uint32_t i : indices) keep(i);
    return out;
}

}  // namespace twinrender::realtime
