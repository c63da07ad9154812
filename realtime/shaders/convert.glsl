// Float-to-integer conversions with a defined answer for every input. GLSL leaves int(x) and
// uint(x) undefined for a NaN, an infinity or a value beyond the integer's range: NVIDIA gives 0
// for NaN, saturates, and 0 for a negative float to uint; llvmpipe (x86) gives INT_MIN to int
// and 0xFFFFFFFF to uint (x <= -1 too) for all of them. A float a shader computed is converted
// here:
//  clampToInt(x, lo, hi)  trunc(x) within [lo, hi] (lo <= hi); NaN gives lo. Indices (a cell,
//                         a texel), loop counts (to a stated maximum), sizes.
//  saturateToInt(x)       trunc(x) within +-2^30, beyond every image and grid with room to add a
//                         block's size; NaN gives -2^30: off the image, an empty walk. A finite
//                         x beyond int is expected (a walk's bound in a level far away:
//                         telescope.toml's planet lies 1e12 cells of the rock's level away).
//  toIndex(x)             an index carried as a float (a material, a body): clampToInt(x, 0,
//                         2^30) as a uint, NaN 0. No bound from the array: a buffer's length()
//                         counts poison mode's tail (gl/buffer.cpp); C++ refuses an index past it.
//  toInt(x), toUint(x)    int(x), uint(x): a bad input gives the driver's answer (or the mode's).
// Exempt, left as int(), ivec2(): gl_FragCoord.xy, gl_GlobalInvocationID and integer expressions
// (whole and in range), and uniforms C++ sets to whole numbers (an image's size, a direction).
// GLSL leaves min, max and clamp undefined for a NaN too: the helpers test NaN (by its bits, which
// no compiler folds away) before clamping; elsewhere a NaN that can matter is tested first:
// per_set.glsl's levelOf (a NaN ratio is level 0), per_set_grid.comp's LAYOUT (a box no cell
// size fits is one cell), shade.frag's shadow-map bounds (a NaN point is lit).
//
// Test modes (realtime/gl/conversions.h, TWINRENDER_GL_CONVERSIONS): CONVERSIONS_SATURATE makes
// toInt and toUint answer as NVIDIA, CONVERSIONS_WRAP as llvmpipe; clampToInt and saturateToInt
// answer alike in every mode. CONVERSIONS_COUNT: every call with a non-finite or out-of-range
// value (saturateToInt: a non-finite one) adds 1 to the atomic counter at binding 0, which C++
// checks after each pass and stage.

bool isNanBits(float x) { return (floatBitsToUint(x) & 0x7FFFFFFFu) > 0x7F800000u; }
bool isFiniteBits(float x) { return (floatBitsToUint(x) & 0x7F800000u) != 0x7F800000u; }
// Whether trunc(x) is an int / a uint (false for NaN and infinities).
bool inIntRange(float x) { return !isNanBits(x) && x >= -2147483648.0 && x < 2147483648.0; }
bool inUintRange(float x) { return !isNanBits(x) && x > -1.0 && x < 4294967296.0; }

#ifdef CONVERSIONS_COUNT
layout(binding = 0, offset = 0) uniform atomic_uint uConversionCount;
#define COUNT_UNLESS(inRange) \
    if (!(inRange)) atomicCounterIncrement(uConversionCount)
#else
#define COUNT_UNLESS(inRange)
#endif

const int INT_MIN_ = int(0x80000000u);

int toInt(float x) {
    COUNT_UNLESS(inIntRange(x));
#if defined(CONVERSIONS_SATURATE)
    if (isNanBits(x)) return 0;
    return x >= 2147483648.0 ? 0x7FFFFFFF : x < -2147483648.0 ? INT_MIN_ : int(x);
#elif defined(CONVERSIONS_WRAP)
    return inIntRange(x) ? int(x) : INT_MIN_;  // cvttss2si's "integer indefinite"
#else
    return int(x);
#endif
}

uint toUint(float x) {
    COUNT_UNLESS(inUintRange(x));
#if defined(CONVERSIONS_SATURATE)
    if (isNanBits(x) || x <= 0.0) return 0u;
    return x >= 4294967296.0 ? 0xFFFFFFFFu : uint(x);
#elif defined(CONVERSIONS_WRAP)
    return inUintRange(x) ? uint(x) : 0xFFFFFFFFu;  // llvmpipe's (-2.5 too, not 0xFFFFFFFE)
#else
    return uint(x);
#endif
}

int clampToInt(float x, int lo, int hi) {
    COUNT_UNLESS(inIntRange(x));
    // Saturated to int's range (2147483520 is the largest float below 2^31), then clamped.
    return isNanBits(x) ? lo : clamp(int(clamp(x, -2147483648.0, 2147483520.0)), lo, hi);
}

const float SATURATED_INT = 1073741824.0;  // 2^30
int saturateToInt(float x) {
    COUNT_UNLESS(isFiniteBits(x));
    return int(isNanBits(x) ? -SATURATED_INT : clamp(x, -SATURATED_INT, SATURATED_INT));
}
uint toIndex(float x) { return uint(clampToInt(x, 0, 1 << 30)); }

ivec2 saturateToInt(vec2 x) { return ivec2(saturateToInt(x.x), saturateToInt(x.y)); }
ivec3 saturateToInt(vec3 x) {
    return ivec3(saturateToInt(x.x), saturateToInt(x.y), saturateToInt(x.z));
}
