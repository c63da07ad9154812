#include "raymarch/interval_bounds.h"

#include <cmath>

#include "core/sph_kernel.h"
#include "raymarch/vector_loops.h"

namespace twinrender::raymarch {

namespace {

// A particle's largest value on [a, b] (parameters relative to the field's base): at the point
// nearest it, 0 where its support misses the interval.
inline float largestOn(float tc, float d2, float coef, float ih2, float a, float b) {
    const float tn = minf(maxf(tc, a), b) - tc;
    return coef * core::m4ShapeInSupport(std::sqrt(minf((tn * tn + d2) * ih2, 4.0f)));
}

}  // namespace

TWINRENDER_VECTOR_CLONES
double intervalBound(const RayField& field, double t, double tEnd) {
    const RayField::Lanes f = field.lanes();
    const float x = static_cast<float>(t - f.base);
    const float xEnd = static_cast<float>(tEnd - f.base);
    const std::size_t n = f.padded;
    if (n % LANES != 0) __builtin_unreachable();
    const float *tcs = f.tc, *d2s = f.d2, *coefs = f.coef, *ih2s = f.ih2;
    float bound = 0.0f;
#pragma omp simd reduction(+ : bound)
    for (std::size_t i = 0; i < n; ++i) {
        bound += largestOn(tcs[i], d2s[i], coefs[i], ih2s[i], x, xEnd);
    }
    // Float rounding must not turn the bound into an underestimate.
    return bound * (1.0 + 1e-5);
}

TWINRENDER_VECTOR_CLONES
void piecewiseBound(const RayField& field, const double (&points)[BOUND_PIECES + 1],
                    double (&bounds)[BOUND_PIECES]) {
    const RayField::Lanes f = field.lanes();
    float x[BOUND_PIECES + 1];
    for (int k = 0; k <= BOUND_PIECES; ++k) x[k] = static_cast<float>(points[k] - f.base);
    const std::size_t n = f.padded;
    if (n % LANES != 0) __builtin_unreachable();
    const float *tcs = f.tc, *d2s = f.d2, *coefs = f.coef, *ih2s = f.ih2;
    float b0 = 0.0f, b1 = 0.0f, b2 = 0.0f;
    static_assert(BOUND_PIECES == 3);
#pragma omp simd reduction(+ : b0, b1, b2)
    for (std::size_t i = 0; i < n; ++i) {
        const float tc = tcs[i], d2 = d2s[i], coef = coefs[i], ih2 = ih2s[i];
        float largest[BOUND_PIECES];
        for (int k = 0; k < BOUND_PIECES; ++k)
            largest[k] = largestOn(tc, d2, coef, ih2, x[k], x[k + 1]);
        b0 += largest[0];
        b1 += largest[1];
        b2 += largest[2];
    }
    // Float rounding must not turn the bounds into underestimates.
    bounds[0] = b0 * (1.0 + 1e-5);
    bounds[1] = b1 * (1.0 + 1e-5);
    bounds[2] = b2 * (1.0 + 1e-5);
}

}  // namespace twinrender::raymarch
