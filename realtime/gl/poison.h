// Poison mode: with the environment variable TWINRENDER_GL_POISON set (and not "0"), every
// buffer made without contents (Buffer::storage) and every texture is filled with a poison
// pattern when it is made, and a storage buffer that is kept for another use is poisoned again
// (per_set_gpu.cpp). llvmpipe hands out zeroed memory, so a read of memory nobody wrote reads
// zero there and passes; a GPU hands out whatever the memory held. Under poison such a read
// reads poisonWord(): by default (any value but "finite") POISON_NAN_WORD, a NaN as a float and
// an index far out of range as a uint; with TWINRENDER_GL_POISON=finite, POISON_FINITE_WORD, a
// large finite float, which a comparison or a min/max treats as a number: a read that a NaN's
// handling on llvmpipe (comparisons false, min/max taking the other operand) would hide still
// changes the answer.
#pragma once

#include <cstdint>

namespace twinrender::realtime::gl {

inline constexpr std::uint32_t POISON_NAN_WORD = 0x7FBADBADu;
// 6.7e18 as a float; 1,589,304,237 as a uint.
inline constexpr std::uint32_t POISON_FINITE_WORD = 0x5EBADBADu;
inline constexpr float POISON_DEPTH = 0.3f;  // depth targets: any value in [0, 1] but a clear's

enum class PoisonPattern { Off, Nan, Finite };

// TWINRENDER_GL_POISON's pattern: unset, empty or "0" Off, "finite" Finite, anything else Nan
// (read once per process).
PoisonPattern poisonPattern();
// Whether TWINRENDER_GL_POISON is set (poisonPattern() is not Off).
bool poisonMode();
// The word poison mode fills with (POISON_NAN_WORD outside poison mode).
std::uint32_t poisonWord();

}  // namespace twinrender::realtime::gl
