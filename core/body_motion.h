// How a generated body moves over a sequence (BodyDesc::velocity, spin, churn): at time t (s)
// of frame n it is the body generated at its centre c, turned about c by |spin| t degrees
// about spin's direction and carried by velocity t; then, with churn > 0, each particle is
// displaced by a new random vector each frame, uniform in a ball of radius churn x h (the
// particles of an SPH fluid reordering under a still surface). The random vectors come from
// splitmix64 seeded by the body's seed and the frame number: the same frame always gets the
// same displacements, on any machine.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <span>

#include "core/particles.h"
#include "core/scene.h"

namespace twinrender::core {

// Moves the body's generated particles (`position`, scene units, all with smoothing length
// `h`) and its uv frame (`info`: centre and axes) to time `time` of frame `frame`.
void applyMotion(const BodyDesc& body, double time, std::int64_t frame,
                 std::span<glm::vec3> position, double h, BodyInfo& info);

}  // namespace twinrender::core
