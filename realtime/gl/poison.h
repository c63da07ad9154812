// Poison mode: with the environment variable TWINRENDER_GL_POISON set (and not "0"), every
// buffer made without contents (Buffer::storage) and every texture is filled with a poison
// pattern when it is made, and a storage buffer that is kept for another use is poisoned again
// (per_set_gpu.cpp). llvmpipe hands out zeroed memory, so a read of memory nobody wrote reads
// zero there and passes; a GPU hands out whatever the memory held. Under poison such a read
// reads POISON_WORD: a NaN as a float, an index far out of range as a uint.
#pragma once

#include <cstdint>

namespace twinrender::realtime::gl {

inline constexpr std::uint32_t POISON_WORD = 0x7FBADBADu;
inline constexpr float POISON_DEPTH = 0.3f;  // depth targets: any value in [0, 1] but a clear's

// Whether TWINRENDER_GL_POISON is set (read once per process).
bool poisonMode();

}  // namespace twinrender::realtime::gl
