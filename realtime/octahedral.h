// Octahedral encoding of unit vectors (Cigolle et al. 2014): the G-buffer stores normals in
// two floats. The C++ twin of octEncode / octDecode in shaders/common.glsl, for reading back.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace twinrender::realtime {

glm::vec2 octEncode(glm::vec3 unit);
glm::vec3 octDecode(glm::vec2 encoded);  // unit

}  // namespace twinrender::realtime
