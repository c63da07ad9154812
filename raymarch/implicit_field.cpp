#include "raymarch/implicit_field.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <numbers>

#include "core/sph_kernel.h"

namespace twinrender::raymarch {

using core::m4Shape;

// Value (not reference) minimum and maximum: std::min's reference result keeps a branch in
// the loops, which stops them from being vectorised.
inline float minf(float a, float b) { return a < b ? a : b; }
inline float maxf(float a, float b) { return a > b ? a : b; }

namespace {

// An inert candidate (padding, or a particle whose support misses the segment): outside its
// support everywhere (q^2 = (dt^2 + 4) * 1 >= 4) and weightless.
constexpr float INERT_D2 = 4.0f;
// A batch's padding: a zero support meets no ray.
constexpr FieldParticle INERT_PARTICLE{0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f};

// A bracketed hit's tBelow is taken this fraction of the tolerance before the end of the
// proven-safe step, so that rounding cannot put it on the level.
constexpr double BELOW_MARGIN = 0.01;
// The lower bound is solved for a bracket only once the bracket's estimate, (M - m) step^2 /
// (2 phi'), is within this factor of the tolerance (a square root saved on most steps).
constexpr double BRACKET_ESTIMATE_SLACK = 4.0;
// The bound that lets a search jump to its hint is taken over [ta, hint] in pieces that end
// these fractions of the step window before the hint.
constexpr double HINT_PIECES[] = {0.2, 0.05};

// The M4 shape w(q) and w'(q)/q for q in [0, 2]; the inner branch of w'/q needs no division
// and stays finite at q = 0.
inline float shape(float q) {
    const float a = 2.0f - q;
    return q < 1.0f ? 1.0f - 1.5f * q * q + 0.75f * q * q * q : 0.25f * a * a * a;
}
inline float shapeDerivativeOverQ(float q) {
    const float a = 2.0f - q;
    return q < 1.0f ? -3.0f + 2.25f * q : -0.75f * a * a / q;
}


}  // namespace

bool makeCandidate(const double origin[3], const double direction[3], const double center[3],
                   double h, double volume, std::uint32_t index, Candidate& out) {
    const double w[3] = {center[0] - origin[0], center[1] - origin[1], center[2] - origin[2]};
    const double tc = w[0] * direction[0] + w[1] * direction[1] + w[2] * direction[2];
    // Perpendicular offset computed directly (not |w|^2 - tc^2), which cancels far away.
    const double p[3] = {w[0] - tc * direction[0], w[1] - tc * direction[1], w[2] - tc * direction[2]};
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
    out.peak = out.coef * m4Shape(std::sqrt(d2) * out.invH);
    out.index = index;
    return true;
}

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

void RayField::resize(std::size_t n) {
    mCount = n;
    mPadded = (n + LANES - 1) / LANES * LANES;
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

void RayField::assign(const std::vector<Candidate>& candidates, double base) {
    mBase = base;
    const std::size_t n = candidates.size();
    resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Candidate& c = candidates[i];
        mTc[i] = static_cast<float>(c.tc - base);
        mD2[i] = static_cast<float>(c.d2);
        mCoef[i] = static_cast<float>(c.coef);
        mIh2[i] = static_cast<float>(c.invH * c.invH);
        mPeak[i] = static_cast<float>(c.peak);
        mIndex[i] = c.index;
    }
    mCandidates = n;
    mPeakSum = 0.0;
    for (const Candidate& c : candidates) mPeakSum += c.peak;
}

// The vector loops run 8 lanes wide with fused multiply-adds where the CPU has x86-64-v3
// (AVX2, FMA; chosen at run time), 4 lanes otherwise. One machine always takes the same
// clone, so results stay bit-identical run to run.
#define TWINRENDER_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))

void ParticleBatch::assign(std::span<const std::uint32_t> prims, const std::vector<FieldParticle>& particles,
                           const HitAttributes* attributes) {
    const std::size_t n = prims.size(), padded = (n + RayField::LANES - 1) / RayField::LANES * RayField::LANES;
    for (auto* v : {&mX, &mY, &mZ, &mSupport2, &mCoef, &mInvH2}) v->resize(padded);
    mIndex.resize(padded);
    if (attributes) {
        for (auto* v : {&mU, &mV, &mR, &mG, &mB}) v->resize(padded);
        for (std::size_t i = 0; i < padded; ++i) {
            const HitAttributes a = i < n ? attributes[prims[i]] : HitAttributes{};
            mU[i] = a.u;
            mV[i] = a.v;
            mR[i] = a.r;
            mG[i] = a.g;
            mB[i] = a.b;
        }
    } else {
        for (auto* v : {&mU, &mV, &mR, &mG, &mB}) v->clear();
    }
    // Relative to a particle of the batch, the positions keep float's relative precision at
    // the scale of the batch (a few h), wherever it lies.
    const FieldParticle& first = n > 0 ? particles[prims[0]] : INERT_PARTICLE;
    mOrigin = glm::dvec3(first.x, first.y, first.z);
    for (std::size_t i = 0; i < padded; ++i) {
        const FieldParticle& p = i < n ? particles[prims[i]] : INERT_PARTICLE;
        mX[i] = static_cast<float>(double(p.x) - mOrigin.x);
        mY[i] = static_cast<float>(double(p.y) - mOrigin.y);
        mZ[i] = static_cast<float>(double(p.z) - mOrigin.z);
        mSupport2[i] = p.support2;
        mCoef[i] = p.coef;
        mInvH2[i] = p.invH2;
        mIndex[i] = i < n ? prims[i] : 0;
    }
}

TWINRENDER_VECTOR_CLONES
bool ParticleBatch::average(const float* weights, std::size_t count, HitAttributes& out) const {
    if (count % RayField::LANES != 0) __builtin_unreachable();
    float heaviest = 0.0f;
#pragma omp simd reduction(max : heaviest)
    for (std::size_t i = 0; i < count; ++i) heaviest = maxf(heaviest, weights[i]);
    if (!(heaviest > 0.0f)) return false;
    std::size_t first = 0;
    while (weights[first] != heaviest) ++first;
    const float uRef = mU[first];
    const float *us = mU.data(), *vs = mV.data(), *rs = mR.data(), *gs = mG.data(), *bs = mB.data();
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

TWINRENDER_VECTOR_CLONES
void RayField::build(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax,
                     const ParticleBatch& batch) {
    mBase = tMin;
    const std::size_t n = batch.size();
    if (n % LANES != 0) __builtin_unreachable();
    resize(n);
    float* tc = mTc;
    float* d2 = mD2;
    float* coef = mCoef;
    float* ih2 = mIh2;
    float* peak = mPeak;
    const float *px = batch.mX.data(), *py = batch.mY.data(), *pz = batch.mZ.data(),
                *support2 = batch.mSupport2.data(), *pcoef = batch.mCoef.data(), *pih2 = batch.mInvH2.data();
    // The segment's start relative to the batch's origin.
    const glm::dvec3 start = (origin - batch.mOrigin) + tMin * direction;
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
        const float largest = pc * shape(std::sqrt(minf(e2 * h2, 4.0f)));
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
    std::copy(batch.mIndex.begin(), batch.mIndex.end(), mIndex.begin());
}

TWINRENDER_VECTOR_CLONES
double RayField::supportStart() const {
    const std::size_t n = mPadded;
    if (n % LANES != 0) __builtin_unreachable();
    const float *tcs = mTc, *d2s = mD2, *ih2s = mIh2;
    float first = INFINITY;
#pragma omp simd reduction(min : first)
    for (std::size_t i = 0; i < n; ++i) {
        // Half the chord of the support sphere: sqrt((2h)^2 - d2) = sqrt((4 - d2 / h^2) / (1 / h^2)).
        const float delta2 = d2s[i] * ih2s[i];
        const float half = std::sqrt(maxf(4.0f - delta2, 0.0f) / ih2s[i]);
        first = minf(first, delta2 < 4.0f ? tcs[i] - half : INFINITY);
    }
    return mBase + first;
}

TWINRENDER_VECTOR_CLONES
FieldSample RayField::sample(double t, double window, double horizon) const {
    const float x = static_cast<float>(t - mBase);
    const float xEnd = static_cast<float>(t + window - mBase);
    const float xAhead = static_cast<float>(t + horizon - mBase);
    const std::size_t n = mPadded;
    // Whole vectors only (the padding is inert): no scalar remainder loop.
    if (n % LANES != 0) __builtin_unreachable();
    const float *tcs = mTc, *d2s = mD2, *coefs = mCoef, *ih2s = mIh2, *peaks = mPeak;
    float value = 0.0f, slope = 0.0f, curvature = 0.0f, curvatureLow = 0.0f, ahead = 0.0f;
#pragma omp simd reduction(+ : value, slope, curvature, curvatureLow, ahead)
    for (std::size_t i = 0; i < n; ++i) {
        // Every operand loaded up front: a load under a condition becomes a masked load.
        const float tc = tcs[i], d2 = d2s[i], coef = coefs[i], ih2 = ih2s[i], peak = peaks[i];
        const float k = coef * ih2;
        const float dt = x - tc;
        const float q2 = (dt * dt + d2) * ih2;
        const float q = std::sqrt(minf(q2, 4.0f));
        const float w = shape(q);
        value += coef * w;
        // d/dt w(q) = w'(q) dq/dt with dq/dt = dt / (q h^2).
        slope += k * shapeDerivativeOverQ(q) * dt;
        // Curvature bounds over the window (header): q^2 is smallest at the closest approach
        // within the window and largest at one of its ends.
        const float tn = minf(maxf(tc, x), xEnd) - tc;
        const float qmin2 = (tn * tn + d2) * ih2;
        const float dtEnd = xEnd - tc;
        const float qmax2 = maxf(q2, (dtEnd * dtEnd + d2) * ih2);
        const float delta2 = d2 * ih2;
        const float outer = 1.0f - delta2 / qmax2;
        const float upper = qmin2 >= 1.0f   ? 0.5f * (4.0f - qmin2) * outer
                            : qmax2 <= 1.0f ? -0.75f + 2.25f * (qmax2 - delta2)
                                            : 1.5f * outer;
        const float lower = qmin2 >= 1.0f ? -0.75f : -3.0f;
        const bool inWindow = qmin2 < 4.0f;
        curvature += inWindow ? k * upper : 0.0f;
        curvatureLow += inWindow ? k * lower : 0.0f;
        // Each particle at its largest value over [x, xAhead]: its value at x when the closest
        // approach lies behind (0 past its support), else its peak when its support begins
        // before xAhead (q^2 < 4 at the nearer of xAhead and the closest approach).
        const float dtAhead = minf(tc, xAhead) - tc;
        const bool reached = (dtAhead * dtAhead + d2) * ih2 < 4.0f;
        ahead += tc >= x ? (reached ? peak : 0.0f) : coef * w;
    }
    // Float rounding must not turn the bounds into underestimates.
    constexpr double SAFETY = 1e-5;
    return {value, slope, curvature + std::abs(curvature) * SAFETY,
            curvatureLow - std::abs(curvatureLow) * SAFETY, ahead * (1.0 + SAFETY)};
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

TWINRENDER_VECTOR_CLONES
FieldSample RayField::sampleValue(double t) const {
    const float x = static_cast<float>(t - mBase);
    const std::size_t n = mPadded;
    if (n % LANES != 0) __builtin_unreachable();
    const float *tcs = mTc, *d2s = mD2, *coefs = mCoef, *ih2s = mIh2;
    float value = 0.0f, slope = 0.0f;
#pragma omp simd reduction(+ : value, slope)
    for (std::size_t i = 0; i < n; ++i) {
        const float tc = tcs[i], d2 = d2s[i], coef = coefs[i], ih2 = ih2s[i];
        const float dt = x - tc;
        const float q = std::sqrt(minf((dt * dt + d2) * ih2, 4.0f));
        value += coef * shape(q);
        slope += coef * ih2 * shapeDerivativeOverQ(q) * dt;
    }
    FieldSample f;
    f.value = value;
    f.slope = slope;
    return f;
}

double RayField::remainingBound(double t, double tEnd) const { return sample(t, 0.0, tEnd - t).ahead; }

TWINRENDER_VECTOR_CLONES
double RayField::intervalBound(double t, double tEnd) const {
    const float x = static_cast<float>(t - mBase);
    const float xEnd = static_cast<float>(tEnd - mBase);
    const std::size_t n = mPadded;
    if (n % LANES != 0) __builtin_unreachable();
    const float *tcs = mTc, *d2s = mD2, *coefs = mCoef, *ih2s = mIh2;
    float bound = 0.0f;
#pragma omp simd reduction(+ : bound)
    for (std::size_t i = 0; i < n; ++i) {
        // Each particle at the point of [x, xEnd] nearest it (0 where its support misses).
        const float tc = tcs[i], d2 = d2s[i], coef = coefs[i], ih2 = ih2s[i];
        const float tn = minf(maxf(tc, x), xEnd) - tc;
        bound += coef * shape(std::sqrt(minf((tn * tn + d2) * ih2, 4.0f)));
    }
    // Float rounding must not turn the bound into an underestimate.
    return bound * (1.0 + 1e-5);
}

TWINRENDER_VECTOR_CLONES
void RayField::piecewiseBound(const double (&points)[PIECES + 1], double (&bounds)[PIECES]) const {
    float x[PIECES + 1];
    for (int k = 0; k <= PIECES; ++k) x[k] = static_cast<float>(points[k] - mBase);
    const std::size_t n = mPadded;
    if (n % LANES != 0) __builtin_unreachable();
    const float *tcs = mTc, *d2s = mD2, *coefs = mCoef, *ih2s = mIh2;
    float b0 = 0.0f, b1 = 0.0f, b2 = 0.0f;
    static_assert(PIECES == 3);
#pragma omp simd reduction(+ : b0, b1, b2)
    for (std::size_t i = 0; i < n; ++i) {
        const float tc = tcs[i], d2 = d2s[i], coef = coefs[i], ih2 = ih2s[i];
        float largest[PIECES];
        for (int k = 0; k < PIECES; ++k) {
            const float tn = minf(maxf(tc, x[k]), x[k + 1]) - tc;
            largest[k] = coef * shape(std::sqrt(minf((tn * tn + d2) * ih2, 4.0f)));
        }
        b0 += largest[0];
        b1 += largest[1];
        b2 += largest[2];
    }
    // Float rounding must not turn the bounds into underestimates.
    bounds[0] = b0 * (1.0 + 1e-5);
    bounds[1] = b1 * (1.0 + 1e-5);
    bounds[2] = b2 * (1.0 + 1e-5);
}

TWINRENDER_VECTOR_CLONES
SurfacePoint RayField::surfacePoint(double t, std::vector<float>& weights) const {
    const float s = static_cast<float>(t - mBase);
    const std::size_t n = mPadded;
    if (n % LANES != 0) __builtin_unreachable();
    weights.resize(n);
    const float *tcs = mTc, *d2s = mD2, *coefs = mCoef, *ih2s = mIh2, *exs = mEx, *eys = mEy, *ezs = mEz;
    const glm::vec3 d = mDirection;
    float* weight = weights.data();
    float gx = 0.0f, gy = 0.0f, gz = 0.0f, largest = 0.0f;  // of 1 / h^2
#pragma omp simd reduction(+ : gx, gy, gz) reduction(max : largest)
    for (std::size_t i = 0; i < n; ++i) {
        const float dt = s - tcs[i], coef = coefs[i], ih2 = ih2s[i];
        const float q = std::sqrt(minf((dt * dt + d2s[i]) * ih2, 4.0f));
        weight[i] = coef * shape(q);
        largest = maxf(largest, weight[i] > 0.0f ? ih2 : 0.0f);
        // grad f = c w'(q) grad q = c (w'(q) / q) (p - x) / h^2, with p - x = dt d - e.
        const float g = coef * shapeDerivativeOverQ(q) * ih2;
        gx += g * (dt * d.x - exs[i]);
        gy += g * (dt * d.y - eys[i]);
        gz += g * (dt * d.z - ezs[i]);
    }
    return {{gx, gy, gz}, largest > 0.0f ? 1.0 / std::sqrt(double(largest)) : 0.0};
}

namespace {

// Smallest s >= 0 at which value + slope s + curvature s^2 / 2 reaches the level (value below
// it); infinity when it never does.
double firstReach(double value, double slope, double curvature, double level) {
    const double gap = level - value;
    const double disc = slope * slope + 2.0 * curvature * gap;
    if (disc < 0.0) return INFINITY;  // a downward parabola peaking below the level
    const double root = std::sqrt(disc);
    // Written to avoid cancellation when slope > 0.
    if (slope > 0.0) return 2.0 * gap / (slope + root);
    return curvature > 0.0 ? (root - slope) / curvature : INFINITY;
}

}  // namespace

TWINRENDER_VECTOR_CLONES
Crossing findFirstCrossing(const RayField& field, double ta, double tb,
                           const CrossingSettings& settings, double hint) {
    Crossing out;
    const double level = settings.level, tolerance = settings.tolerance;
    double a = ta;
    if (hint > ta && hint < tb) {
        ++out.evaluations;
        // Pieces shorter toward the hint, where phi comes closest to the level; the search
        // starts after the last of the pieces that begin it proven below the level.
        const double points[] = {ta, std::max(ta, hint - HINT_PIECES[0] * settings.maxStep),
                                 std::max(ta, hint - HINT_PIECES[1] * settings.maxStep), hint};
        double bounds[RayField::PIECES];
        field.piecewiseBound(points, bounds);
        for (int k = 0; k < RayField::PIECES && bounds[k] < level; ++k) a = points[k + 1];
    }
    double previous = a;
    // The curvature bounds of the last full sample hold up to boundsEnd: while the window left
    // reaches past the last step (converging on a root, the steps shrink), phi and phi' alone
    // suffice.
    double boundsEnd = -INFINITY, upper = 0.0, lower = 0.0, lastStep = INFINITY;
    for (int it = 0; it < settings.maxIterations; ++it) {
        double window = boundsEnd - a;
        FieldSample f;
        if (window >= lastStep) {
            f = field.sampleValue(a);
            f.curvature = upper;
            f.curvatureLow = lower;
            f.ahead = INFINITY;
        } else {
            window = std::min(settings.maxStep, tb - a);
            f = field.sample(a, window, tb - a);
            boundsEnd = a + window;
            upper = f.curvature;
            lower = f.curvatureLow;
        }
        ++out.evaluations;
        if (f.value >= level) {
            // At the start: the ray begins inside. Later the step can only land exactly on the
            // root (the bound touches the level there): a hit.
            out.status = it == 0 && a == ta ? Crossing::Status::Inside : Crossing::Status::Hit;
            out.t = a;
            out.tBelow = it == 0 ? a : previous;
            return out;
        }
        previous = a;
        if (f.ahead < level) {
            // Nothing ahead can reach the level.
            out.status = Crossing::Status::Miss;
            out.tBelow = tb;
            return out;
        }
        // phi < level on [a, a + step); phi(a + sure) >= level.
        const double step = firstReach(f.value, f.slope, f.curvature, level);
        const bool nearRoot =
            (f.curvature - f.curvatureLow) * step * step <= 2.0 * BRACKET_ESTIMATE_SLACK * tolerance * f.slope;
        const double sure = nearRoot ? firstReach(f.value, f.slope, f.curvatureLow, level) : INFINITY;
        // Going away from the surface (a shadow ray leaving its start): phi stays below the
        // level up to the next point; the bound of what lies beyond is cheaper than a sample.
        const double next = a + std::min(step, window);
        if (f.slope <= 0.0 && next < tb && field.intervalBound(next, tb) < level) {
            ++out.evaluations;
            out.status = Crossing::Status::Miss;
            out.tBelow = tb;
            return out;
        }
        if (sure <= window && sure - step <= tolerance) {
            // The first root is bracketed within the tolerance: take the Newton estimate
            // inside the bracket.
            out.status = Crossing::Status::Hit;
            out.t = a + std::clamp((level - f.value) / f.slope, step, sure);
            out.tBelow = a + std::max(0.0, step - BELOW_MARGIN * tolerance);
            return out;
        }
        if (step < tolerance) {
            // The bound says the root may be closer than the tolerance: confirm it.
            const double b = a + tolerance;
            const FieldSample fb = field.sampleValue(b);
            ++out.evaluations;
            if (fb.value >= level) {
                const double frac = (level - f.value) / (fb.value - f.value);
                out.status = Crossing::Status::Hit;
                out.tBelow = a;
                out.t = a + tolerance * std::clamp(frac, 0.0, 1.0);
                return out;
            }
            a = b;  // grazing past a tangency; the next step starts below the level
            lastStep = tolerance;
        } else {
            lastStep = std::min(step, window);
            a += lastStep;
        }
        if (a >= tb) {
            out.status = Crossing::Status::Miss;
            out.tBelow = tb;
            return out;
        }
    }
    out.status = Crossing::Status::Unresolved;
    out.tBelow = a;
    return out;
}

}  // namespace twinrender::raymarch
