// convert.glsl's helpers over a list of inputs, one invocation each (realtime/
// conversions_gl_test.cpp): toInt, toUint (as int bits), clampToInt(x, -5, 5), saturateToInt.
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
    outputs[i] = ivec4(toInt(x), int(toUint(x)), clampToInt(x, -5, 5), saturateToInt(x));
}
