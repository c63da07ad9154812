#include "core/emitters.h"

#include <algorithm>
#include <glm/geometric.hpp>

#include "core/shading.h"

namespace twinrender::core {

BodySphere bodySphere(const ParticleSet& ps, const BodyInfo& info) {
    BodySphere out;
    if (info.end <= info.begin) return out;
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    double hSum = 0.0;
    for (std::size_t i = info.begin; i < info.end; ++i) {
        const glm::dvec3 p(ps.position[i]);
        lo = glm::min(lo, p - 2.0 * double(ps.h[i]));
        hi = glm::max(hi, p + 2.0 * double(ps.h[i]));
        hSum += ps.h[i];
    }
    out.centre = 0.5 * (lo + hi);
    double centres = 0.0;
    for (std::size_t i = info.begin; i < info.end; ++i) {
        const double d = glm::length(glm::dvec3(ps.position[i]) - out.centre);
        out.radius = std::max(out.radius, d + 2.0 * double(ps.h[i]));
        centres = std::max(centres, d);
    }
    out.surfaceRadius = centres + 0.5 * hSum / double(info.end - info.begin);
    return out;
}

std::vector<EmittingBody> emittingBodies(const SceneParticles& particles,
                                         const std::vector<Material>& materials) {
    std::vector<EmittingBody> out;
    const ParticleSet& ps = particles.particles;
    for (std::uint32_t b = 0; b < particles.bodies.size(); ++b) {
        const BodyInfo& info = particles.bodies[b];
        if (info.end <= info.begin || info.material >= materials.size()) continue;
        const Material& material = materials[info.material];
        glm::dvec3 sum(0.0);
        bool emits = false;
        for (std::size_t i = info.begin; i < info.end; ++i) {
            const glm::vec3 e = surfaceEmission(material, ps.uv[i], ps.glow[i]);
            emits = emits || e.r > 0.0f || e.g > 0.0f || e.b > 0.0f;
            sum += glm::dvec3(e);
        }
        if (!emits) continue;
        const BodySphere sphere = bodySphere(ps, info);
        out.push_back({.body = b,
                       .centre = sphere.centre,
                       .radius = sphere.radius,
                       .surfaceRadius = sphere.surfaceRadius,
                       .meanRadiance = sum / double(info.end - info.begin)});
    }
    return out;
}

}  // namespace twinrender::core
