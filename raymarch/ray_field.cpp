#include "raymarch/ray_field.h"

#include <algorithm>
#include <cmath>

#include "core/sph_kernel.h"
#include "raymarch/vector_loops.h"

namespace twinrender::raymarch {

namespace {

// An inert candidate (padding, or a particle whose support misses the segment): outside its
// support everywhere (q^2 = (dt^2 + 4) * 1 >= 4) and weightless.
constexpr float INERT_D2 = 4.0f;

}  // namespace

void RayField::resize(std::size_t n) {
    mCount = n;
    mPadded = padToLanes(n);
    if (mIndex.size() < mPadded) {
        constexpr std::size_t ARRAYS = 8;
        const std::size_t capacity = 2 * mPadded;
        mStore.resize(ARRAYS * capacity);
        mIndex.resize(capacity);
        float* p = mStore.data();
        for (float** a : {&mTc, &mD2, &mCoef, &mIh2, &mPeak, &mEx, &mEy, &mEz}) {
            *a = p;
            p += capacity;
        }
    }
    for (std::size_t i = n; i < mPadded; ++i) {
        mTc[i] = 0.0f;
        mD2[i] = INERT_D2;
        mCoef[i] = mPeak[i] = 0.0f;
        mIh2[i] = 1.0f;
        mEx[i] = mEy[i] = mEz[i] = 0.0f;
        mIndex[i] = 0;  // a valid particle (there is one whenever there is padding)
    }
}

TWINRENDER_VECTOR_CLONES
void RayField::build(const glm::dvec3& origin, const glm::dvec3& direction, double tMin,
                     double tMax, const ParticleBatch& batch) {
    mBase = tMin;
    const std::size_t n = batch.size();
    if (n % LANES != 0) __builtin_unreachable();
    resize(n);
    float* tc = mTc;
    float* d2 = mD2;
    float* coef = mCoef;
    float* ih2 = mIh2;
    float* peak = mPeak;
    const ParticleBatch::Arrays& b = batch.arrays();
    const float *px = b.x.data(), *py = b.y.data(), *pz = b.z.data(), *support2 = b.support2.data(),
                *pcoef = b.coef.data(), *pih2 = b.invH2.data();
    // The segment's start relative to the batch's origin.
    const glm::dvec3 start = (origin - b.origin) + tMin * direction;
    const float sx = static_cast<float>(start.x), sy = static_cast<float>(start.y),
                sz = static_cast<float>(start.z);
    const float dx = static_cast<float>(direction.x), dy = static_cast<float>(direction.y),
                dz = static_cast<float>(direction.z);
    const float length = static_cast<float>(tMax - tMin);
    mDirection = {dx, dy, dz};
    float *ex = mEx, *ey = mEy, *ez = mEz;
    // Every particle of the batch, in its order (the summation order).
    float peaks = 0.0f;
    int overlapping = 0;
#pragma omp simd reduction(+ : overlapping, peaks)
    for (std::size_t i = 0; i < n; ++i) {
        const float wx = px[i] - sx, wy = py[i] - sy, wz = pz[i] - sz;
        const float c = wx * dx + wy * dy + wz * dz;
        // Perpendicular offset computed directly (not |w|^2 - c^2, which cancels).
        const float ox = wx - c * dx, oy = wy - c * dy, oz = wz - c * dz;
        const float e2 = ox * ox + oy * oy + oz * oz;
        const float chord2 = support2[i] - e2;
        // The support interval (c -+ sqrt(chord2)) overlaps [0, length]: the point of the
        // segment nearest its centre lies inside it (no square root).
        const float outside = minf(maxf(c, 0.0f), length) - c;
        const bool overlaps = (chord2 > 0.0f) & (outside * outside < chord2);
        // Loaded unconditionally: a load under a condition becomes a masked load.
        const float pc = pcoef[i], h2 = pih2[i];
        const float largest = pc * core::m4ShapeInSupport(std::sqrt(minf(e2 * h2, 4.0f)));
        // The others become inert.
        tc[i] = overlaps ? c : 0.0f;
        d2[i] = overlaps ? e2 : INERT_D2;
        coef[i] = overlaps ? pc : 0.0f;
        ih2[i] = overlaps ? h2 : 1.0f;
        peak[i] = overlaps ? largest : 0.0f;
        ex[i] = ox;
        ey[i] = oy;
        ez[i] = oz;
        overlapping += overlaps;
        peaks += overlaps ? largest : 0.0f;
    }
    mCandidates = overlapping;
    // Float rounding must not turn the bound into an underestimate.
    mPeakSum = peaks * (1.0 + 1e-5);
    std::copy(b.index.begin(), b.index.end(), mIndex.begin());
}

TWINRENDER_VECTOR_CLONES
double RayField::supportStart() const {
    const std::size_t n = mPadded;
    if (n % LANES != 0) __builtin_unreachable();
    const float *tcs = mTc, *d2s = mD2, *ih2s = mIh2;
    float first = INFINITY;
#pragma omp simd reduction(min : first)
    for (std::size_t i = 0; i < n; ++i) {
        // Half the chord of the support sphere: sqrt((2h)^2 - d2) = sqrt((4 - d2 / h^2) / (1 /
        // h^2)).
        const float delta2 = d2s[i] * ih2s[i];
        const float half = std::sqrt(maxf(4.0f - delta2, 0.0f) / ih2s[i]);
        first = minf(first, delta2 < 4.0f ? tcs[i] - half : INFINITY);
    }
    return mBase + first;
}

TWINRENDER_VECTOR_CLONES
double RayField::largestHBeyond(double t) const {
    const float x = static_cast<float>(t - mBase);
    const std::size_t n = mPadded;
    if (n % LANES != 0) __builtin_unreachable();
    const float *tcs = mTc, *d2s = mD2, *ih2s = mIh2;
    float smallest = INFINITY;  // of 1 / h^2
#pragma omp simd reduction(min : smallest)
    for (std::size_t i = 0; i < n; ++i) {
        // The support interval ends after x: its centre lies ahead, or x lies inside it.
        const float ih2 = ih2s[i], delta2 = d2s[i] * ih2, dt = x - tcs[i];
        const bool beyond = (delta2 < 4.0f) & ((dt < 0.0f) | (dt * dt * ih2 + delta2 < 4.0f));
        smallest = minf(smallest, beyond ? ih2 : INFINITY);
    }
    return std::isfinite(smallest) ? 1.0 / std::sqrt(double(smallest)) : 0.0;
}

}  // namespace twinrender::raymarch
