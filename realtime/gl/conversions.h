// Test modes of the shaders' float-to-integer conversions (realtime/shaders/convert.glsl), set by
// the environment variable TWINRENDER_GL_CONVERSIONS (read once per process): GLSL leaves
// int(x) and uint(x) undefined for a NaN, an infinity or a value beyond the integer's range, and
// NVIDIA and llvmpipe answer differently, so a test that passes on llvmpipe says nothing of
// NVIDIA where such a value reaches a conversion.
//  - "saturate": convert.glsl's toInt / toUint answer as NVIDIA does (NaN 0, saturated to the
//    range, a negative float to uint 0); "wrap": as llvmpipe on x86 does (NaN and out of range
//    INT_MIN to int, 0xFFFFFFFF to uint, a float <= -1 to uint too);
//  - "count" (alone or after either, "saturate,count"): every helper called with a non-finite
//    or out-of-range value adds 1 to a counter (an atomic counter buffer at
//    CONVERSION_COUNTER_BINDING, which each context binds when it is made), and
//    checkConversions, after each pass and per-set stage, throws naming it when the counter is
//    not 0.
// The shader library prepends conversionDefines() to every program it compiles.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "realtime/gl/buffer.h"

namespace twinrender::realtime::gl {

enum class ConversionMode {
    Native,    // the driver's own conversion
    Saturate,  // NVIDIA's answers
    Wrap,      // x86's (llvmpipe's)
};

struct Conversions {
    ConversionMode mode = ConversionMode::Native;
    bool count = false;  // count the conversions of non-finite or out-of-range values
};

// The atomic counter buffer binding of convert.glsl's counter (no program uses another).
inline constexpr unsigned CONVERSION_COUNTER_BINDING = 0;

// "", "saturate", "wrap", "count", "saturate,count", "wrap,count" ("count,wrap" too); throws
// core::InputError naming TWINRENDER_GL_CONVERSIONS and its values for anything else.
Conversions parseConversions(std::string_view value);
// TWINRENDER_GL_CONVERSIONS parsed (read once per process; unset: Native, no count).
const Conversions& conversionsMode();
// The #defines of convert.glsl's test modes: CONVERSIONS_SATURATE or CONVERSIONS_WRAP, and
// CONVERSIONS_COUNT.
std::vector<std::string> conversionDefines(const Conversions& conversions = conversionsMode());

// The counter of convert.glsl's CONVERSIONS_COUNT: one uint, zero when made, bound at
// CONVERSION_COUNTER_BINDING by bind(). A context makes and binds one when counting
// (context.cpp); a test may bind its own.
class ConversionCounter {
  public:
    ConversionCounter();
    void bind() const;
    // The count since it was made or last taken (waits for the shaders before), set back to 0.
    std::uint32_t take();
    // take(); throws gl::Error naming `stage` and the count when it is not 0.
    void check(std::string_view stage);

  private:
    Buffer mBuffer;
};

// Counting: checks the counter bound at CONVERSION_COUNTER_BINDING (the context's) as
// ConversionCounter::check does, naming "KIND 'NAME'" ("pass 'shade'"). Else nothing.
void checkConversions(std::string_view kind, std::string_view name);

}  // namespace twinrender::realtime::gl
