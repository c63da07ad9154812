#include "core/emitters.h"

#include "core/body_sphere.h"
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
        glm::dvec3 sum(0.0);
        bool emits = false;
        for (std::size_t i = info.begin; i < info.end; ++i) {
            const glm::vec3 e = surfaceEmission(material, ps.uv[i], ps.glow[i]);
            emits = emits || e.r > 0.0f || e.g > 0.0f || e.b > 0.0f;
            sum += glm::dvec3(e);
        }
        if (!emits) continue;
        const double n = double(info.end - info.begin);
        const BodyBounds bounds = bodyBounds(ps, info);
        EmittingBody e;
        e.body = b;
        e.centre = bounds.centre;
        e.radius = bounds.radius;
        e.surfaceRadius = bounds.particles + 0.5 * bounds.meanH;
        e.meanRadiance = sum / n;
        out.push_back(e);
    }
    return out;
}

}  // namespace twinrender::core
