// Test helpers for the ray field (ray_field.h): fields built from a particle set as the
// renderer builds them, fields built in double from particles given one at a time (no
// bundle gather, no particle batch), the field summed in double, and the analytic radius of
// one particle's level set.
#pragma once

#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <numbers>
#include <numeric>
#include <vector>

#include "core/particles.h"
#include "core/sph_kernel.h"
#include "raymarch/field_sample.h"
#include "raymarch/hit_attributes.h"
#include "raymarch/particle_batch.h"
#include "raymarch/ray_field.h"

namespace twinrender::raymarch::testing {

// Twenty particles of several sizes scattered around the x axis over x in [0, 6].
inline core::ParticleSet particlesAroundXAxis() {
    core::ParticleSet ps;
    ps.resize(20);
    for (int i = 0; i < 20; ++i) {
        ps.position[i] = {0.3f * i, 0.5f * std::sin(1.7f * i), 0.4f * std::cos(0.9f * i)};
        ps.h[i] = 0.4f + 0.05f * (i % 4);
        ps.volume[i] = 0.02f + 0.001f * i;
    }
    return ps;
}

// The field of the ray origin + t direction on [tMin, tMax] as the renderer builds it: every
// particle of `ps` in one batch, in order (with their attributes when given).
inline void buildField(RayField& field, ParticleBatch& batch, const core::ParticleSet& ps,
                       const glm::dvec3& origin, const glm::dvec3& direction, double tMin,
                       double tMax, const std::vector<HitAttributes>* attributes = nullptr) {
    std::vector<std::uint32_t> prims(ps.size());
    std::iota(prims.begin(), prims.end(), 0u);
    batch.assign(prims, makeFieldParticles(ps), attributes ? attributes->data() : nullptr);
    field.build(origin, direction, tMin, tMax, batch);
}

// phi(p) summed in double over every particle of `ps`.
inline double fieldInDouble(const core::ParticleSet& ps, const glm::dvec3& p) {
    double phi = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i)
        phi += ps.volume[i] *
               core::m4Kernel(glm::length(p - glm::dvec3(ps.position[i])), double(ps.h[i]));
    return phi;
}

// One particle along a ray, in double.
struct Candidate {
    double tc;  // ray parameter of the closest approach to the particle
    double d2;  // squared distance of the particle from the ray line
    double t0;  // support interval (t0, t1) on the ray
    double t1;
    double coef;  // v / (pi h^3)
    double invH;  // 1 / h
    double peak;  // the largest contribution along the ray: coef * w(sqrt(d2) / h)
    std::uint32_t index;
};

// Builds the candidate of a particle at `center` for a ray (origin, unit direction); returns
// false when the ray line misses its support sphere.
inline bool makeCandidate(const double origin[3], const double direction[3], const double center[3],
                          double h, double volume, std::uint32_t index, Candidate& out) {
    const double w[3] = {center[0] - origin[0], center[1] - origin[1], center[2] - origin[2]};
    const double tc = w[0] * direction[0] + w[1] * direction[1] + w[2] * direction[2];
    // Perpendicular offset computed directly (not |w|^2 - tc^2), which cancels far away.
    const double p[3] = {w[0] - tc * direction[0], w[1] - tc * direction[1],
                         w[2] - tc * direction[2]};
    const double d2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
    const double support = core::M4_SUPPORT * h;
    const double chord2 = support * support - d2;
    if (chord2 <= 0.0) return false;
    const double half = std::sqrt(chord2);
    out.tc = tc;
    out.d2 = d2;
    out.t0 = tc - half;
    out.t1 = tc + half;
    out.invH = 1.0 / h;
    out.coef = volume / (std::numbers::pi * h * h * h);
    out.peak = out.coef * core::m4Shape(std::sqrt(d2) * out.invH);
    out.index = index;
    return true;
}

// The candidates of particles of smoothing length h and volume v at `centers` for the ray
// along +x from the origin: those whose support the ray meets, in order.
inline std::vector<Candidate> candidatesAlongX(const std::vector<glm::dvec3>& centers, double h,
                                               double v) {
    const double origin[3] = {0.0, 0.0, 0.0}, direction[3] = {1.0, 0.0, 0.0};
    std::vector<Candidate> out;
    for (std::size_t i = 0; i < centers.size(); ++i) {
        const double center[3] = {centers[i].x, centers[i].y, centers[i].z};
        Candidate c;
        if (makeCandidate(origin, direction, center, h, v, static_cast<std::uint32_t>(i), c))
            out.push_back(c);
    }
    return out;
}

struct RayFieldAccess {
    // The field of `candidates` (in any fixed order: it is the summation order), with ray
    // parameters relative to `base` (a ray parameter near them). No direction or offsets:
    // not for surfacePoint().
    static void assign(RayField& field, const std::vector<Candidate>& candidates, double base) {
        field.mBase = base;
        const std::size_t n = candidates.size();
        field.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const Candidate& c = candidates[i];
            field.mTc[i] = static_cast<float>(c.tc - base);
            field.mD2[i] = static_cast<float>(c.d2);
            field.mCoef[i] = static_cast<float>(c.coef);
            field.mIh2[i] = static_cast<float>(c.invH * c.invH);
            field.mPeak[i] = static_cast<float>(c.peak);
            field.mIndex[i] = c.index;
        }
        field.mCandidates = n;
        field.mPeakSum = 0.0;
        for (const Candidate& c : candidates) field.mPeakSum += c.peak;
    }
};

inline void assign(RayField& field, const std::vector<Candidate>& candidates, double base) {
    RayFieldAccess::assign(field, candidates, base);
}

// An upper bound of phi on [t, tEnd]: each particle at its largest value there (its peak
// when the closest approach lies ahead, its value at t when it lies behind).
inline double remainingBound(const RayField& field, double t, double tEnd) {
    return sampleField(field, t, 0.0, tEnd - t).ahead;
}

// Radius r at which one particle's field v W(r, h) equals the level: bisection on the
// monotone kernel, independent of the raymarcher's root finder.
inline double singleParticleRadius(double v, double h, double level) {
    double lo = 0.0, hi = 2.0 * h;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (v * core::m4Kernel(mid, h) > level ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace twinrender::raymarch::testing
