// convert.glsl's helpers over a list of inputs, one invocation each (realtime/
// conversions_gl_test.cpp): toInt, toUint (as int bits), clampToInt(x, -5, 5), saturateToInt;
// then toIndex.
#include "convert.glsl"

layout(local_size_x = 1) in;
layout(std430, binding = 0) readonly buffer Inputs {
    float inputs[];
};
layout(std430, binding = 1) writeonly buffer Outputs {
    ivec4 outputs[];
};

void main() {
    uint i = gl_GlobalInvocationID.x;
    float x = inputs[i];
    outputs[2u * i] = ivec4(toInt(x), int(toUint(x)), clampToInt(x, -5, 5), saturateToInt(x));
    outputs[2u * i + 1u] = ivec4(int(toIndex(x)), 0, 0, 0);
}
