#include "raymarch/particle_batch.h"

#include <numbers>

#include "core/sph_kernel.h"
#include "raymarch/hit_attributes.h"
#include "raymarch/vector_loops.h"

namespace twinrender::raymarch {

namespace {

// A batch's padding: a zero support meets no ray.
constexpr FieldParticle INERT_PARTICLE{0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f};

}  // namespace

std::vector<FieldParticle> makeFieldParticles(const core::ParticleSet& ps) {
    std::vector<FieldParticle> out(ps.size());
    for (std::size_t i = 0; i < ps.size(); ++i) {
        const double h = ps.h[i], support = core::M4_SUPPORT * h;
        out[i] = {ps.position[i].x,
                  ps.position[i].y,
                  ps.position[i].z,
                  static_cast<float>(support * support),
                  static_cast<float>(ps.volume[i] / (std::numbers::pi * h * h * h)),
                  static_cast<float>(1.0 / (h * h))};
    }
    return out;
}

void ParticleBatch::assign(std::span<const std::uint32_t> prims,
                           const std::vector<FieldParticle>& particles,
                           const HitAttributes* attributes) {
    Arrays& a = mArrays;
    const std::size_t n = prims.size(), padded = padToLanes(n);
    for (auto* v : {&a.x, &a.y, &a.z, &a.support2, &a.coef, &a.invH2}) v->resize(padded);
    a.index.resize(padded);
    if (attributes) {
        for (auto* v : {&a.u, &a.v, &a.r, &a.g, &a.b}) v->resize(padded);
        for (std::size_t i = 0; i < padded; ++i) {
            const HitAttributes h = i < n ? attributes[prims[i]] : HitAttributes{};
            a.u[i] = h.u;
            a.v[i] = h.v;
            a.r[i] = h.r;
            a.g[i] = h.g;
            a.b[i] = h.b;
        }
    } else {
        for (auto* v : {&a.u, &a.v, &a.r, &a.g, &a.b}) v->clear();
    }
    const FieldParticle& first = n > 0 ? particles[prims[0]] : INERT_PARTICLE;
    a.origin = glm::dvec3(first.x, first.y, first.z);
    for (std::size_t i = 0; i < padded; ++i) {
        const FieldParticle& p = i < n ? particles[prims[i]] : INERT_PARTICLE;
        a.x[i] = static_cast<float>(double(p.x) - a.origin.x);
        a.y[i] = static_cast<float>(double(p.y) - a.origin.y);
        a.z[i] = static_cast<float>(double(p.z) - a.origin.z);
        a.support2[i] = p.support2;
        a.coef[i] = p.coef;
        a.invH2[i] = p.invH2;
        a.index[i] = i < n ? prims[i] : 0;
    }
}

}  // namespace twinrender::raymarch
