// Blackbody glow: the emitted radiance of a body at a temperature, as a linear sRGB colour.
#pragma once

#include <glm/vec3.hpp>

namespace twinrender::core {

// Planck's law integrated against the CIE 1931 colour-matching functions (the analytic fit
// of Wyman, Sloan & Shirley 2013), converted to linear sRGB (negative components clamped),
// scaled so that 1500 K has luminance Y = 1. Below about 800 K it is negligible (Y < 1e-3).
// The fit, not the integration, sets the accuracy against the CIE 1931 table: it moves the
// Planckian chromaticity by (-0.0044, +0.0044) in (x, y) at 1500 K, (-0.0012, +0.0010) at
// 2856 K (illuminant A; core/blackbody_test.cpp) and 1e-4 at 6000 K, and the luminance ratio
// Y(6000 K) / Y(3000 K) by -0.12 %.
glm::vec3 blackbodyRadiance(double kelvin);

}  // namespace twinrender::core
