#include "core/renderer.h"

namespace twinrender::core {

// Defined here, so the vtable has one home.
Renderer::~Renderer() = default;

}  // namespace twinrender::core
