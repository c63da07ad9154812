// The exact Euclidean distance transform of a binary image, for silhouette distances and the
// interior erosion (masks.h).
//
// P. F. Felzenszwalb, D. P. Huttenlocher, "Distance Transforms of Sampled Functions", Theory
// of Computing 8(19), 415-428, 2012. The squared distance transform of a sampled function f is
// the lower envelope of the parabolas (x - q)^2 + f(q); in two dimensions it separates into a
// 1-D transform of every column followed by one of every row, each linear in the pixel count.
// Exact (no chamfer approximation): the result is min over feature pixels q of |p - q|^2.
#pragma once

#include <vector>

#include "compare/masks.h"

namespace twinrender::compare {

// Squared Euclidean distance, in pixels^2, from every pixel centre to the nearest pixel inside
// `features` (0 on the features themselves); +infinity everywhere when `features` is empty.
// One value a pixel, row-major. Deterministic for any thread count (each row and column is
// transformed independently).
std::vector<float> squaredDistanceTransform(const Mask& features);

}  // namespace twinrender::compare
