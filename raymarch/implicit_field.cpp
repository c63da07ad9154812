#include "raymarch/implicit_field.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/sph_kernel.h"

namespace twinrender::raymarch {

using core::m4Shape;
using core::m4ShapeDerivative;

// Value (not reference) minimum and maximum: std::min's reference result keeps a branch in
// the loops, which stops them from being vectorised.
inline float minf(float a, float b) { return a < b ? a : b; }
inline float maxf(float a, float b) { return a > b ? a : b; }

// Upper bound of w''(q) along a line, see the header.
constexpr float W_CURVATURE_BOUND = 1.5f;

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

void RayField::assign(const std::vector<Candidate>& candidates, double base) {
    mBase = base;
    const std::size_t n = candidates.size();
    for (auto* v : {&mTc, &mD2, &mT0, &mT1, &mCoef, &mIh2, &mPeak}) v->resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Candidate& c = candidates[i];
        mTc[i] = static_cast<float>(c.tc - base);
        mD2[i] = static_cast<float>(c.d2);
        mT0[i] = static_cast<float>(c.t0 - base);
        mT1[i] = static_cast<float>(c.t1 - base);
        mCoef[i] = static_cast<float>(c.coef);
        mIh2[i] = static_cast<float>(c.invH * c.invH);
        mPeak[i] = static_cast<float>(c.peak);
    }
}

// The vector loops run 8 lanes wide where the CPU has AVX2 (chosen at run time), 4 otherwise.
// One machine always takes the same clone, so results stay bit-identical run to run.
#define TWINRENDER_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))

TWINRENDER_VECTOR_CLONES
FieldSample RayField::sample(double t, double window) const {
    const float x = static_cast<float>(t - mBase);
    const float xEnd = static_cast<float>(t + window - mBase);
    const std::size_t n = mT0.size();
    const float* t0 = mT0.data();
    const float* tc = mTc.data();
    const float* d2 = mD2.data();
    const float* t1 = mT1.data();
    const float* coef = mCoef.data();
    const float* ih2 = mIh2.data();
    float value = 0.0f, slope = 0.0f, curvature = 0.0f;
#pragma omp simd reduction(+ : value, slope, curvature)
    for (std::size_t i = 0; i < n; ++i) {
        const float dt = x - tc[i];
        const float q = std::sqrt(minf((dt * dt + d2[i]) * ih2[i], 4.0f));
        const float a = 2.0f - q;
        // w and dw/dq of the M4 spline; both vanish at q = 2, outside the support.
        const float w = q < 1.0f ? 1.0f - 1.5f * q * q + 0.75f * q * q * q : 0.25f * a * a * a;
        const float dw = q < 1.0f ? -3.0f * q + 2.25f * q * q : -0.75f * a * a;
        value += coef[i] * w;
        // d/dt w(q) = w'(q) dq/dt with dq/dt = dt / (q h^2); dw/q -> -3 as q -> 0.
        slope += coef[i] * dw * dt * ih2[i] / maxf(q, 1e-30f);
        // Curvature bound over the window: max(w'', 0) <= 1.5, and <= 1.5 (2 - q) beyond
        // q = 1, taken at the closest approach within the window; as sqrt is concave,
        // 2 - q <= (4 - q^2) / 3 on [1, 2], which spares a square root. And
        // (dq/dt)^2 <= (1 - d2/4h^2) / h^2.
        const float tn = minf(maxf(tc[i], x), xEnd) - tc[i];
        const float qn2 = minf((tn * tn + d2[i]) * ih2[i], 4.0f);
        const float wb = qn2 <= 1.0f ? W_CURVATURE_BOUND : W_CURVATURE_BOUND * (4.0f - qn2) / 3.0f;
        const float active = (t1[i] > x) & (t0[i] < xEnd) ? 1.0f : 0.0f;
        curvature += active * coef[i] * wb * maxf(0.0f, 1.0f - 0.25f * d2[i] * ih2[i]) * ih2[i];
    }
    return {value, slope, curvature};
}

TWINRENDER_VECTOR_CLONES
double RayField::remainingBound(double t, double tEnd) const {
    const float x = static_cast<float>(t - mBase);
    const float xEnd = static_cast<float>(tEnd - mBase);
    const std::size_t n = mT0.size();
    const float* t0 = mT0.data();
    const float* tc = mTc.data();
    const float* d2 = mD2.data();
    const float* t1 = mT1.data();
    const float* coef = mCoef.data();
    const float* ih2 = mIh2.data();
    const float* peak = mPeak.data();
    float bound = 0.0f;
#pragma omp simd reduction(+ : bound)
    for (std::size_t i = 0; i < n; ++i) {
        const float dt = x - tc[i];
        const float q = std::sqrt(minf((dt * dt + d2[i]) * ih2[i], 4.0f));
        const float a = 2.0f - q;
        const float w = q < 1.0f ? 1.0f - 1.5f * q * q + 0.75f * q * q * q : 0.25f * a * a * a;
        const float ahead = peak[i], behind = coef[i] * w;
        const float here = tc[i] >= x ? ahead : behind;
        bound += (t1[i] > x) & (t0[i] < xEnd) ? here : 0.0f;
    }
    // Float rounding must not turn the bound into an underestimate.
    return bound * (1.0 + 1e-5);
}

namespace {

// Smallest s >= 0 with value + slope s + curvature s^2 / 2 = level (value < level).
double safeStep(const FieldSample& f, double level) {
    const double gap = level - f.value;
    if (f.curvature > 0.0) {
        const double disc = f.slope * f.slope + 2.0 * f.curvature * gap;
        // Written to avoid cancellation when slope > 0: s = 2 gap / (slope + sqrt(disc)).
        const double root = std::sqrt(disc);
        return f.slope > 0.0 ? 2.0 * gap / (f.slope + root) : (root - f.slope) / f.curvature;
    }
    return f.slope > 0.0 ? gap / f.slope : INFINITY;
}

}  // namespace

Crossing findFirstCrossing(const RayField& field, double ta, double tb,
                           const CrossingSettings& settings) {
    Crossing out;
    const double level = settings.level;
    double a = ta;
    double previous = a;
    for (int it = 0; it < settings.maxIterations; ++it) {
        const double window = std::min(settings.maxStep, tb - a);
        const FieldSample f = field.sample(a, window);
        ++out.evaluations;
        if (f.value >= level) {
            // At the start: the ray begins inside. Later the step can only land exactly on the
            // root (the bound touches the level there): a hit.
            out.status = it == 0 ? Crossing::Status::Inside : Crossing::Status::Hit;
            out.t = a;
            out.tBelow = it == 0 ? a : previous;
            return out;
        }
        previous = a;
        // Going away from the surface: stop once nothing ahead can reach the level.
        if (f.slope < 0.0 && field.remainingBound(a, tb) < level) {
            ++out.evaluations;
            out.status = Crossing::Status::Miss;
            out.tBelow = tb;
            return out;
        }
        const double step = safeStep(f, level);
        if (step < settings.tolerance) {
            // The bound says the root may be closer than the tolerance: confirm it.
            const double b = a + settings.tolerance;
            const FieldSample fb = field.sample(b, 0.0);
            ++out.evaluations;
            if (fb.value >= level) {
                const double frac = (level - f.value) / (fb.value - f.value);
                out.status = Crossing::Status::Hit;
                out.tBelow = a;
                out.t = a + settings.tolerance * std::clamp(frac, 0.0, 1.0);
                return out;
            }
            a = b;  // grazing past a tangency; the next step starts below the level
        } else if (step >= window) {
            a += window;
        } else {
            a += step;
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
