#include "core/renderer.h"

#include <fmt/format.h>

#include "core/error.h"

namespace twinrender::core {

// Defined here, so the vtable has one home.
Renderer::~Renderer() = default;

void requireWholeFrame(const RenderInput& input, std::string_view renderer) {
    if (!input.part.whole())
        throw InputError(fmt::format(
            "part {}/{} of a frame: the {} renderer draws whole frames only; the reference "
            "raymarcher renders parts (--tiles K/N with --renderer raymarch)",
            input.part.index, input.part.count, renderer));
}

}  // namespace twinrender::core
