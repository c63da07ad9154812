// Blackbody glow: the emitted radiance of a body at a temperature, as a linear sRGB colour.
#pragma once

#include <glm/vec3.hpp>

namespace twinrender::core {

// Planck's law integrated against the CIE 1931 colour-matching functions (the analytic fit
// of Wyman, Sloan & Shirley 2013), converted to linear sRGB (negative components clamped),
// scaled so that 1500 K has luminance Y = 1. Below about 800 K it is negligible (Y < 1e-3).
glm::vec3 blackbodyRadiance(double kelvin);

}  // namespace twinrender::core
