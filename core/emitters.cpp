#include "core/emitters.h"

#include <algorithm>
#include <glm/geometric.hpp>

#include "core/shading.h"

namespace twinrender::core {

std::vector<EmittingBody> emittingBodies(const SceneParticles& particles,
                                         const std::vector<Material>& materials) {
    std::vector<EmittingBody> out;
    const ParticleSet& ps = particles.particles;
    for (std::uint32_t b = 0; b < particles.bodies.size(); ++b) {
        const BodyInfo& info = particles.bodies[b];
        if (info.end <= info.begin || info.material >= materials.size()) continue;
        const Material& material = materials[info.material];
        glm::dvec3 sum(0.0), lo(INFINITY), hi(-INFINITY);
        double hSum = 0.0;
        bool emits = false;
        for (std::size_t i = info.begin; i < info.end; ++i) {
            const glm::vec3 e = surfaceEmission(material, ps.uv[i], ps.glow[i]);
            emits = emits || e.r > 0.0f || e.g > 0.0f || e.b > 0.0f;
            sum += glm::dvec3(e);
            const glm::dvec3 p(ps.position[i]);
            lo = glm::min(lo, p - 2.0 * double(ps.h[i]));
            hi = glm::max(hi, p + 2.0 * double(ps.h[i]));
            hSum += ps.h[i];
        }
        if (!emits) continue;
        const double n = double(info.end - info.begin);
        EmittingBody e;
        e.body = b;
        e.centre = 0.5 * (lo + hi);
        double centres = 0.0;
        for (std::size_t i = info.begin; i < info.end; ++i) {
            const double d = glm::length(glm::dvec3(ps.position[i]) - e.centre);
            e.radius = std::max(e.radius, d + 2.0 * double(ps.h[i]));
            centres = std::max(centres, d);
        }
        e.surfaceRadius = centres + 0.5 * hSum / n;
        e.meanRadiance = sum / n;
        out.push_back(e);
    }
    return out;
}

}  // namespace twinrender::core
