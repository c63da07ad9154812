// The colour-field kernels of every particle (realtime/gpu_scene.h, GpuKernel, std430), for the
// passes that sum the field itself rather than draw impostors.
struct Kernel {
    vec4 positionSupport;  // camera-relative world position; support radius 2 h (scene units)
    vec4 coefficients;     // x: v / (pi h^4) (dW/dr = x w'(r / h)); y: 1 / h
};

layout(std430, binding = 3) readonly buffer Kernels {
    Kernel kernels[];
};
