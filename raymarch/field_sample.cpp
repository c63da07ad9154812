#include "raymarch/field_sample.h"

#include <cmath>

#include "core/sph_kernel.h"
#include "raymarch/vector_loops.h"

namespace twinrender::raymarch {

using core::m4ShapeDerivativeOverQ;
using core::m4ShapeInSupport;

TWINRENDER_VECTOR_CLONES
FieldSample sampleField(const RayField& field, double t, double window, double horizon) {
    const RayField::Lanes f = field.lanes();
    const float x = static_cast<float>(t - f.base);
    const float xEnd = static_cast<float>(t + window - f.base);
    const float xAhead = static_cast<float>(t + horizon - f.base);
    const std::size_t n = f.padded;
    // Whole vectors only (the padding is inert): no scalar remainder loop.
    if (n % LANES != 0) __builtin_unreachable();
    const float *tcs = f.tc, *d2s = f.d2, *coefs = f.coef, *ih2s = f.ih2, *peaks = f.peak;
    float value = 0.0f, slope = 0.0f, curvature = 0.0f, curvatureLow = 0.0f, ahead = 0.0f;
#pragma omp simd reduction(+ : value, slope, curvature, curvatureLow, ahead)
    for (std::size_t i = 0; i < n; ++i) {
        // Every operand loaded up front: a load under a condition becomes a masked load.
        const float tc = tcs[i], d2 = d2s[i], coef = coefs[i], ih2 = ih2s[i], peak = peaks[i];
        const float k = coef * ih2;
        const float dt = x - tc;
        const float q2 = (dt * dt + d2) * ih2;
        const float q = std::sqrt(minf(q2, 4.0f));
        const float w = m4ShapeInSupport(q);
        value += coef * w;
        // d/dt w(q) = w'(q) dq/dt with dq/dt = dt / (q h^2).
        slope += k * m4ShapeDerivativeOverQ(q) * dt;
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
FieldSample sampleValue(const RayField& field, double t) {
    const RayField::Lanes f = field.lanes();
    const float x = static_cast<float>(t - f.base);
    const std::size_t n = f.padded;
    if (n % LANES != 0) __builtin_unreachable();
    const float *tcs = f.tc, *d2s = f.d2, *coefs = f.coef, *ih2s = f.ih2;
    float value = 0.0f, slope = 0.0f;
#pragma omp simd reduction(+ : value, slope)
    for (std::size_t i = 0; i < n; ++i) {
        const float tc = tcs[i], d2 = d2s[i], coef = coefs[i], ih2 = ih2s[i];
        const float dt = x - tc;
        const float q = std::sqrt(minf((dt * dt + d2) * ih2, 4.0f));
        value += coef * m4ShapeInSupport(q);
        slope += coef * ih2 * m4ShapeDerivativeOverQ(q) * dt;
    }
    FieldSample s;
    s.value = value;
    s.slope = slope;
    return s;
}

}  // namespace twinrender::raymarch
