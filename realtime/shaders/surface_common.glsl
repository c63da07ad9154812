// What the surface passes (realtime/surface_pass.cpp: the depth filters, the normals rebuilt
// from depth, a user's shader) read of the G-buffer. Needs common.glsl. Pixels are integer
// window coordinates (x right, y up); outside the image reads as background.
//  uNormalUv (unit 0): world normal (octahedral, octDecode), u, v
//  uEmission (unit 1): emitted radiance (rgb)
//  uSurface (unit 2): eye depth (+inf on background), body id (-1 on background), the drawn
//                     particle's projected radius in pixels, material index
layout(binding = 0) uniform sampler2D uNormalUv;
layout(binding = 1) uniform sampler2D uEmission;
layout(binding = 2) uniform sampler2D uSurface;

const float BACKGROUND_BODY = -1.0;

bool inImage(ivec2 p) {
    return all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, textureSize(uSurface, 0)));
}

// (eye depth, body, radius px, material); background outside the image.
vec4 surfaceAt(ivec2 p) {
    return inImage(p) ? texelFetch(uSurface, p, 0) : vec4(1.0 / 0.0, BACKGROUND_BODY, 0.0, 0.0);
}
float depthAt(ivec2 p) { return surfaceAt(p).x; }
float bodyAt(ivec2 p) { return surfaceAt(p).y; }
bool coveredAt(ivec2 p) { return surfaceAt(p).y >= 0.0; }
float radiusPxAt(ivec2 p) { return surfaceAt(p).z; }
vec3 normalAt(ivec2 p) { return octDecode(texelFetch(uNormalUv, p, 0).xy); }
vec2 uvAt(ivec2 p) { return texelFetch(uNormalUv, p, 0).zw; }
vec3 emissionAt(ivec2 p) { return texelFetch(uEmission, p, 0).rgb; }

// The drawn particle's radius in scene units at a covered pixel.
float particleRadiusAt(ivec2 p) {
    vec4 s = surfaceAt(p);
    return s.z / pixelsPerUnitAt(s.x);
}

// Eye-space position (x right, y up, looking down -z) of the pixel's centre at eye depth z.
vec3 eyePosition(ivec2 p, float z) {
    vec2 ndc = (vec2(p) + 0.5) * viewport.zw * 2.0 - 1.0;
    float aspect = viewport.x * viewport.w;
    return vec3(ndc.x * tanHalfFovY() * aspect * z, ndc.y * tanHalfFovY() * z, -z);
}

// The world normal of the depth in uSurface at p, a covered pixel of body `body`: per axis
// the one-sided difference with the smaller depth step, over neighbours of the same body
// (Green 2010); `fallback` where an axis has no such neighbour.
vec3 normalFromDepth(ivec2 p, float body, vec3 fallback) {
    vec3 c = eyePosition(p, depthAt(p));
    vec3 d[2];
    for (int axis = 0; axis < 2; ++axis) {
        ivec2 step = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
        ivec2 f = p + step, b = p - step;
        bool okF = bodyAt(f) == body, okB = bodyAt(b) == body;
        if (!okF && !okB) return fallback;
        vec3 df = okF ? eyePosition(f, depthAt(f)) - c : vec3(0.0);
        vec3 db = okB ? c - eyePosition(b, depthAt(b)) : vec3(0.0);
        d[axis] = !okB || (okF && abs(df.z) <= abs(db.z)) ? df : db;
    }
    vec3 n = normalize(cross(d[0], d[1]));
    if (any(isnan(n)) || any(isinf(n))) return fallback;
    return transpose(mat3(viewFromWorld)) * n;
}
