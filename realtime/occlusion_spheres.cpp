#include "realtime/occlusion_spheres.h"

#include <cmath>
#include <numbers>

namespace twinrender::realtime {

std::vector<OcclusionSphere> occlusionSpheres(const core::SceneParticles& scene,
                                              double minFraction) {
    const core::ParticleSet& ps = scene.particles;
    const std::size_t total = ps.size();
    std::vector<double> volume(scene.bodies.size(), 0.0);
    std::vector<glm::dvec3> moment(scene.bodies.size(), glm::dvec3(0.0));
    std::vector<std::size_t> count(scene.bodies.size(), 0);
    for (std::size_t i = 0; i < total; ++i) {
        const std::uint32_t b = ps.body[i];
        if (b >= scene.bodies.size()) continue;
        volume[b] += ps.volume[i];
        moment[b] += static_cast<double>(ps.volume[i]) * glm::dvec3(ps.position[i]);
        ++count[b];
    }
    std::vector<OcclusionSphere> out;
    for (std::uint32_t b = 0; b < scene.bodies.size(); ++b) {
        if (count[b] == 0 || double(count[b]) <= minFraction * double(total) || volume[b] <= 0.0)
            continue;
        OcclusionSphere s;
        s.centre = moment[b] / volume[b];
        s.radius = std::cbrt(3.0 * volume[b] / (4.0 * std::numbers::pi));
        s.body = b;
        out.push_back(s);
    }
    return out;
}

}  // namespace twinrender::realtime
