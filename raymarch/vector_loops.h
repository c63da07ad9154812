// How the raymarcher's loops over particles are vectorised. Their arrays are float, padded
// with inert entries to a whole number of vectors of LANES, and the loops are `#pragma omp
// simd` reductions over whole vectors only (no scalar remainder): they sum in a fixed lane
// order, so results do not depend on the thread that runs them.
#pragma once

#include <cstddef>

// The vector loops run 8 lanes wide with fused multiply-adds where the CPU has x86-64-v3
// (AVX2, FMA; chosen at run time), 4 lanes otherwise. One machine always takes the same
// clone, so results stay bit-identical run to run.
// clang takes target_clones only on a function's first declaration (member functions are
// declared in headers), and its one use here, the instrumented fuzz build (scripts/fuzz),
// needs no clones: there the loops run 4 lanes wide.
#if defined(__clang__)
#define TWINRENDER_VECTOR_CLONES
#else
#define TWINRENDER_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#endif

namespace twinrender::raymarch {

constexpr std::size_t LANES = 8;

// n rounded up to a whole number of vectors.
constexpr std::size_t padToLanes(std::size_t n) {
    return (n + LANES - 1) / LANES * LANES;
}

// Value (not reference) minimum and maximum: std::min's reference result keeps a branch in
// the loops, which stops them from being vectorised.
inline float minf(float a, float b) {
    return a < b ? a : b;
}
inline float maxf(float a, float b) {
    return a > b ? a : b;
}

}  // namespace twinrender::raymarch
