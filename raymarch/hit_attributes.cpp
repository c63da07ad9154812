#include "raymarch/hit_attributes.h"

#include <cmath>

#include "core/sph_kernel.h"
#include "raymarch/vector_loops.h"

namespace twinrender::raymarch {

TWINRENDER_VECTOR_CLONES
SurfacePoint surfacePoint(const RayField& field, double t, std::vector<float>& weights) {
    const RayField::Lanes f = field.lanes();
    const float s = static_cast<float>(t - f.base);
    const std::size_t n = f.padded;
    if (n % LANES != 0) __builtin_unreachable();
    weights.resize(n);
    const float *tcs = f.tc, *d2s = f.d2, *coefs = f.coef, *ih2s = f.ih2, *exs = f.ex, *eys = f.ey,
                *ezs = f.ez;
    const glm::vec3 d = f.direction;
    float* weight = weights.data();
    float gx = 0.0f, gy = 0.0f, gz = 0.0f, largest = 0.0f;  // of 1 / h^2
#pragma omp simd reduction(+ : gx, gy, gz) reduction(max : largest)
    for (std::size_t i = 0; i < n; ++i) {
        const float dt = s - tcs[i], coef = coefs[i], ih2 = ih2s[i];
        const float q = std::sqrt(minf((dt * dt + d2s[i]) * ih2, 4.0f));
        weight[i] = coef * core::m4ShapeInSupport(q);
        largest = maxf(largest, weight[i] > 0.0f ? ih2 : 0.0f);
        // grad f = c w'(q) grad q = c (w'(q) / q) (p - x) / h^2, with p - x = dt d - e.
        const float g = coef * core::m4ShapeDerivativeOverQ(q) * ih2;
        gx += g * (dt * d.x - exs[i]);
        gy += g * (dt * d.y - eys[i]);
        gz += g * (dt * d.z - ezs[i]);
    }
    return {{gx, gy, gz}, largest > 0.0f ? 1.0 / std::sqrt(double(largest)) : 0.0};
}

TWINRENDER_VECTOR_CLONES
bool averageAttributes(const ParticleBatch& batch, const float* weights, std::size_t count,
                       HitAttributes& out) {
    if (count % LANES != 0) __builtin_unreachable();
    float heaviest = 0.0f;
#pragma omp simd reduction(max : heaviest)
    for (std::size_t i = 0; i < count; ++i) heaviest = maxf(heaviest, weights[i]);
    if (!(heaviest > 0.0f)) return false;
    std::size_t first = 0;
    while (weights[first] != heaviest) ++first;
    const ParticleBatch::Arrays& a = batch.arrays();
    const float uRef = a.u[first];
    const float *us = a.u.data(), *vs = a.v.data(), *rs = a.r.data(), *gs = a.g.data(),
                *bs = a.b.data();
    float wsum = 0.0f, u = 0.0f, v = 0.0f, r = 0.0f, g = 0.0f, b = 0.0f;
#pragma omp simd reduction(+ : wsum, u, v, r, g, b)
    for (std::size_t i = 0; i < count; ++i) {
        // Weights outside the support are 0, never negative.
        const float weight = weights[i];
        // u and uRef lie in [0, 1): the nearest integer to their difference is -1, 0 or 1.
        const float du = us[i] - uRef;
        u += weight * (us[i] - (du >= 0.5f ? 1.0f : du <= -0.5f ? -1.0f : 0.0f));
        v += weight * vs[i];
        r += weight * rs[i];
        g += weight * gs[i];
        b += weight * bs[i];
        wsum += weight;
    }
    u /= wsum;
    out = {u - std::floor(u), v / wsum, r / wsum, g / wsum, b / wsum};
    return true;
}

}  // namespace twinrender::raymarch
