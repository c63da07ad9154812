// The colour field along one ray segment, in the layout the field loops want.
//
// phi(x) = sum_j v_j W(|x - x_j|, h_j) (docs/design.md), W the M4 spline (core/sph_kernel.h).
// Along a ray x(t) = o + t d, particle j contributes f_j(t) = c_j w(q_j(t)) with
// c_j = v_j / (pi h_j^3), q_j = sqrt((t - tc_j)^2 + d2_j) / h_j, tc_j its closest-approach
// parameter and d2_j its squared distance from the ray; it is non-zero only on its support
// interval (t0_j, t1_j).
//
// What is computed from a field lives beside it: field_sample.h (phi, phi' and the curvature
// bounds at a point), interval_bounds.h (bounds of phi over intervals), first_crossing.h (the
// root search), hit_attributes.h (normal and averaged attributes at a hit).
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "raymarch/particle_batch.h"

namespace twinrender::raymarch {

namespace testing {
struct RayFieldAccess;
}

// Structure of arrays, float, ray parameters relative to the segment start, so float keeps
// about 1e-7 of the segment's own scale wherever the segment lies. Particles that do not
// overlap the segment stay as inert candidates (removing them costs more than evaluating
// them), and the arrays are padded with inert ones to whole vectors (vector_loops.h).
class RayField {
  public:
    RayField() = default;
    RayField(const RayField&) = delete;  // its arrays point into its own storage
    RayField& operator=(const RayField&) = delete;

    // The field of the ray origin + t direction (unit) on [tMin, tMax] (base = tMin): the
    // particles of `batch` whose support overlaps that interval, in the batch's order. The
    // batch must hold every such particle.
    void build(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax,
               const ParticleBatch& batch);

    // Candidates, the inert ones included (not the padding).
    std::size_t size() const { return mCount; }
    // Candidates whose support overlaps the interval of a build() (the others are inert).
    std::size_t candidates() const { return mCandidates; }
    // Particle index of each candidate.
    const std::uint32_t* indices() const { return mIndex.data(); }
    // The sum of the candidates' peaks: phi stays below it along the whole ray.
    double peakSum() const { return mPeakSum; }
    // Where the first support interval begins (phi = 0 before it); +inf if none. (A pass
    // over the candidates.)
    double supportStart() const;
    // The largest h of the particles whose support reaches past t; 0 if none.
    double largestHBeyond(double t) const;

    // What the field loops read: `padded` entries per array (the padding is inert).
    struct Lanes {
        std::size_t padded;
        double base;                               // the ray parameter the arrays are relative to
        const float *tc, *d2, *coef, *ih2, *peak;  // tc_j - base, d2_j, c_j, 1 / h_j^2, peak
        // build() only: the ray direction and each particle's offset from its closest
        // approach.
        glm::vec3 direction;
        const float *ex, *ey, *ez;
    };
    Lanes lanes() const {
        return {mPadded, mBase, mTc, mD2, mCoef, mIh2, mPeak, mDirection, mEx, mEy, mEz};
    }

  private:
    friend struct testing::RayFieldAccess;  // fields from candidates built in double

    // Makes room for n candidates (contents undefined) and makes the padding inert.
    void resize(std::size_t n);

    double mBase = 0.0;  // the ray parameter the arrays are relative to
    std::size_t mCount = 0;
    std::size_t mPadded = 0;  // mCount rounded up to whole vectors
    std::size_t mCandidates = 0;
    double mPeakSum = 0.0;
    // Ray parameters relative to mBase; one allocation, grown as needed and never shrunk.
    std::vector<float> mStore;
    float *mTc = nullptr, *mD2 = nullptr, *mCoef = nullptr, *mIh2 = nullptr, *mPeak = nullptr;
    // build(): the ray direction and each particle's offset from its closest-approach point.
    glm::vec3 mDirection{0.0f};
    float *mEx = nullptr, *mEy = nullptr, *mEz = nullptr;
    std::vector<std::uint32_t> mIndex;
};

}  // namespace twinrender::raymarch
