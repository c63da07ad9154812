// core::tonemap and core::linearToSrgb (core/shading.cpp), line for line.

float linearToSrgb(float v) {
    v = clamp(v, 0.0, 1.0);
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

// core::tonemap: exposure, the ACES filmic fit (Narkowicz 2015), the sRGB transfer function.
vec3 tonemap(vec3 linear, float exposure) {
    const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
    vec3 out3;
    for (int i = 0; i < 3; ++i) {
        float x = max(linear[i] * exposure, 0.0);
        out3[i] = linearToSrgb(clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0));
    }
    return out3;
}
