// Shared by every pass: the per-frame uniforms (realtime/gpu_scene.h, FrameUniforms, std140)
// and the depth encodings. Positions on the GPU are camera-relative world coordinates: the
// C++ side subtracts the camera position in double precision, so scenes far from the origin
// keep their precision.

layout(std140, binding = 0) uniform FrameUniforms {
    mat4 viewFromWorld;  // rotation only: camera-relative world -> eye (looks down -z)
    mat4 clipFromView;   // the projection used to rasterise (clip range depends on the mode)
    mat4 lightView;      // camera-relative world -> light eye space (looks down -z), scene units
    mat4 lightClip;      // orthographic light projection fitted to the scene bounds
    vec4 viewport;       // width, height, 1/width, 1/height (pixels)
    vec4 camera;         // near, far, tan(fov_y / 2), log2(1 + far / near)
    vec4 light;          // xyz: unit direction the light travels; w: intensity
    vec4 lightColor;     // rgb: linear colour; w: ambient fraction
    vec4 shadowRange;    // x, y: light-space depth of map values 0 and 1; z: texel size (scene
                         // units); w: resolution (texels)
    vec4 shadowBias;     // x: constant bias, y: slope bias (both in max(particle radius, texel));
                         // z: PCF radius (texels); w: tan(sun angular radius)
    vec4 misc;           // x: exposure; y: particle radius scale; z: sphere normal weight;
                         // w: smallest drawn impostor radius (pixels; 0: off)
    vec4 subpixel;       // x: impostors projected smaller than this radius (pixels) give their
                         // emission to a halo (0: off); yzw: unused
};

float cameraNear() { return camera.x; }
float cameraFar() { return camera.y; }
float tanHalfFovY() { return camera.z; }

// Window-space depth of eye depth z > 0 for the selected mode (DEPTH_STANDARD, DEPTH_LOG or
// DEPTH_REVERSED); mirrored by realtime/depth_mapping.h.
float windowDepth(float z) {
    float n = camera.x, f = camera.y;
#if defined(DEPTH_LOG)
    return log2(1.0 + z / n) / camera.w;
#elif defined(DEPTH_REVERSED)
    return n * (f - z) / (z * (f - n));
#else
    return f * (z - n) / (z * (f - n));
#endif
}

// Pixels per scene unit at eye depth z (core::Camera::pixelsPerUnitAt).
float pixelsPerUnitAt(float z) { return 0.5 * viewport.y / (camera.z * z); }

// Camera-relative position of the surface seen through the pixel centre `fragCoord` (OpenGL
// window coordinates, y up) at eye depth z.
vec3 surfacePosition(vec2 fragCoord, float z) {
    vec2 ndc = fragCoord * viewport.zw * 2.0 - 1.0;
    float aspect = viewport.x * viewport.w;
    vec3 eye = vec3(ndc.x * camera.z * aspect * z, ndc.y * camera.z * z, -z);
    return transpose(mat3(viewFromWorld)) * eye;
}

// Octahedral encoding of unit vectors (Cigolle et al. 2014, "A Survey of Efficient
// Representations for Independent Unit Vectors"): a normal in two floats, so that normal and
// uv share one RGBA32F texel. Mirrored by realtime/octahedral.h.
vec2 signNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

vec2 octEncode(vec3 n) {
    vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    return n.z >= 0.0 ? p : (1.0 - abs(p.yx)) * signNotZero(p);
}

vec3 octDecode(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * signNotZero(n.xy);
    return normalize(n);
}
