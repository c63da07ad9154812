// The depth encodings of realtime.depth (docs/scenes.md, realtime.depth), as window-space values in
// [0, 1] from eye depth z in [near, far], and their inverses. shaders/common.glsl (windowDepth)
// writes the same values on the GPU; these are the C++ reference for tests and for reading depth
// back.
#pragma once

#include "realtime/settings.h"

namespace twinrender::realtime {

// log2(1 + z / near) / log2(1 + far / near): 0 at the eye, 1 at far; equal relative depth
// steps get equal buffer steps, so precision does not collapse far away.
double logDepth(double z, double near, double far);
double logDepthToEye(double d, double near, double far);

// The perspective z/w mapped to [0, 1]: far (z - near) / (z (far - near)); 0 at near, 1 at far.
double standardDepth(double z, double near, double far);
double standardDepthToEye(double d, double near, double far);

// Reversed-Z: near (far - z) / (z (far - near)); 1 at near, 0 at far.
double reversedDepth(double z, double near, double far);
double reversedDepthToEye(double d, double near, double far);

double windowDepth(DepthMode mode, double z, double near, double far);
double eyeDepth(DepthMode mode, double d, double near, double far);

// Whether a larger buffer value is nearer (reversed-Z), i.e. the depth test is GREATER.
inline bool nearerIsLarger(DepthMode mode) {
    return mode == DepthMode::Reversed;
}

}  // namespace twinrender::realtime
