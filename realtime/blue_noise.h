// A blue-noise dither texture (the ambient occlusion's ao.noise = "blue"): Ulichney's
// void-and-cluster method (1993) on a torus, so that the tile repeats without seams. Its
// values have little energy at low frequencies: after a blur of a few pixels, the noise they
// drive averages out where white noise leaves blotches.
#pragma once

#include <vector>

namespace twinrender::realtime {

// side x side values (row-major), a permutation of (k + 0.5) / side^2, k = 0 .. side^2 - 1:
// each pixel's rank in the void-and-cluster order. The same for a given side on every run.
// side >= 4.
std::vector<float> blueNoise(int side);

}  // namespace twinrender::realtime
