// The per-set stages of the per-particle models, one per #define: NORMALS (the particle
// normals, where the set came without them), FIELD_NORMAL (field_normal.h's first-order
// model), ANISOTROPY (anisotropy.h's ellipsoids).
#ifdef NORMALS
#define WRITES_ATTRIBUTES  // the normals it derives
#endif
layout(local_size_x = 64) in;
#define USES_RADII
#define USES_MODELS
#define USES_WALKS
#include "per_set_stages.glsl"

#ifdef NORMALS
// core::deriveNormals (derived_attributes.h): -grad c / |grad c| of the colour field at the
// particle, summed over every particle whose support covers it; where the sum cancels below
// (uFallbackRatio + FLT_EPSILON |x| / h) sum |dW/dr| (a lattice's interior), the radial
// direction from the particle's body centre, and the body's pole axis at the centre.
uniform float uFallbackRatio;
uniform int uFromList;  // the particles listed (INTERIOR's, INTERIOR_DRAWN's); else all
const float FLT_EPSILON = 1.1920929e-7;
void main() {
    // All: in grid order (the entries'), so that neighbouring invocations walk the same cells.
    uint i;
    vec3 x;
    if (uFromList != 0) {
        uint t = invocation();
        if (t >= walkDispatch.entries) return;
        i = walkList[t];
        x = particlePosition(i);
    } else {
        uint slot = invocation();
        if (slot >= uCount) return;
        i = entryIndex(slot);
        x = entryPosition(slot).xyz;
    }
    vec3 gradient = vec3(0.0);
    float magnitudeSum = 0.0;
// Outside the support (q >= 2, where dW/dr is 0) and the particle itself are rejected on the
// squared distance, before the square root.
#define ADD_GRADIENT(k)                                                    \
    {                                                                      \
        vec4 e = entryPosition(k);                                         \
        vec3 d = x - e.xyz;                                                \
        float r2 = dot(d, d);                                              \
        if (r2 * (e.w * e.w) < 4.0 && r2 > 0.0) {                          \
            float r = sqrt(r2);                                            \
            float dWdr = entryCoefficients(k).x * m4ShapeDerivative(r * e.w); \
            gradient += (dWdr / r) * d;                                    \
            magnitudeSum -= dWdr;                                          \
        }                                                                  \
    }
    FOR_EACH_NEAR(x, supportReach, ADD_GRADIENT)
#undef ADD_GRADIENT
    float len = length(gradient);
    float resolvable = uFallbackRatio + FLT_EPSILON * length(x) / particleH(i);
    writeNormal(i, len > resolvable * magnitudeSum && len > 0.0 ? -gradient / len
                                                                : fallbackNormal(i, x));
}
#endif

#ifdef FIELD_NORMAL
// field_normal.cpp: the gradient and Hessian of the field at x_top = x_i + r_i n_i, as the
// first-order model of -grad c over the impostor, scaled by 1 / |grad c(x_top)|.
void main() {
    uint i = invocation();
    if (i >= uCount) return;
    float r = radii[i];
    vec3 normal = attribute3(ATTR_NORMAL, i);
    vec3 centre = particlePosition(i);
    vec3 offset = r * normal;
    vec3 point = centre + offset;
    vec3 gradient = vec3(0.0);
    mat3 hessian = mat3(0.0);
#define ADD_DERIVATIVES(k)                                                        \
    {                                                                             \
        vec4 e = entryPosition(k);                                                \
        vec3 delta = offset - (e.xyz - centre);                                   \
        float dist = length(delta);                                               \
        float q = dist * e.w;                                                     \
        if (q < 2.0 && dist > 0.0) {                                              \
            float coef = entryCoefficients(k).x;                                  \
            float dWdr = coef * m4ShapeDerivative(q);                             \
            float d2Wdr2 = coef * e.w * m4ShapeSecondDerivative(q);               \
            vec3 u = delta / dist;                                                \
            gradient += dWdr * u;                                                 \
            hessian += (d2Wdr2 - dWdr / dist) * outerProduct(u, u) + mat3(dWdr / dist); \
        }                                                                         \
    }
    FOR_EACH_NEAR(point, supportReach, ADD_DERIVATIVES)
#undef ADD_DERIVATIVES
    float length_ = length(gradient);
    if (!(length_ > 0.0)) {
        models[3u * i] = vec4(normal, 0.0);
        models[3u * i + 1u] = vec4(0.0);
        models[3u * i + 2u] = vec4(0.0);
        return;
    }
    mat3 m = -hessian / length_;
    models[3u * i] = vec4(-gradient / length_ - m * offset, 0.0);
    models[3u * i + 1u] = vec4(m[0][0], m[1][1], m[2][2], 0.0);
    models[3u * i + 2u] = vec4(m[0][1], m[0][2], m[1][2], 0.0);
}
#endif

#ifdef ANISOTROPY
SYMMETRIC_EIGEN(float, vec3, mat3, 16, 1e-30, 1e-9)
#endif

#ifdef ANISOTROPY
// anisotropy.cpp (Yu & Turk 2013): the weighted covariance of the neighbours within 2 h, its
// eigen-decomposition (core::symmetricEigen's cyclic Jacobi rotations), the clamped spread
// scaled to the impostor sphere's volume, the smoothed and anchored centre. Offsets are in
// units of h (the covariance of order 1 at any scale).
uniform float uSmoothing, uMaxAxisRatio;
uniform int uMinNeighbours, uAnchorSurface;
float ballReach_h;
float ballReach(float hMax) { return ballReach_h; }

void writeSphere(uint i, float r) {
    models[3u * i] = vec4(r, 0.0, 0.0, 0.0);
    models[3u * i + 1u] = vec4(0.0, r, 0.0, 0.0);
    models[3u * i + 2u] = vec4(0.0, 0.0, r, 0.0);
}

void main() {
    uint i = invocation();
    if (i >= uCount) return;
    float r = radii[i];
    if (!(r > 0.0)) {
        writeSphere(i, r);
        return;
    }
    float h = particleH(i);
    vec3 centre = particlePosition(i);
    float radius = 2.0 * h;
    ballReach_h = radius;
    float inverse = 1.0 / radius;
    float weight = 0.0;
    vec3 first = vec3(0.0);
    mat3 second = mat3(0.0);
    int neighbours = 0;
#define GATHER_MOMENTS(k)                                                  \
    {                                                                      \
        vec3 d = entryPosition(k).xyz - centre;                            \
        float q = length(d) * inverse;                                     \
        if (q < 1.0) {                                                     \
            float w = 1.0 - q * q * q;                                     \
            vec3 s = d / h;                                                \
            weight += w;                                                   \
            first += w * s;                                                \
            second += w * outerProduct(s, s);                              \
            neighbours += entryIndex(k) != i ? 1 : 0; \
        }                                                                  \
    }
    FOR_EACH_NEAR(centre, ballReach, GATHER_MOMENTS)
#undef GATHER_MOMENTS
    if (neighbours < uMinNeighbours || !(weight > 0.0)) {
        writeSphere(i, r);
        return;
    }
    vec3 mean = first / weight;
    mat3 c = second / weight - outerProduct(mean, mean);
    vec3 values;
    mat3 vectors;
    symmetricEigen(c, values, vectors);
    float largest = values[0];
    if (!(largest > 0.0)) {
        writeSphere(i, r);
        return;
    }
    vec3 spread = max(values, vec3(largest / uMaxAxisRatio));
    float scale = r / pow(spread.x * spread.y * spread.z, 1.0 / 3.0);
    mat3 axes = mat3(scale * spread[0] * vectors[0], scale * spread[1] * vectors[1],
                     scale * spread[2] * vectors[2]);
    vec3 shift = uSmoothing * mean * h;
    vec3 normal = attribute3(ATTR_NORMAL, i);
    if (uAnchorSurface != 0 && length(normal) > 0.0) {
        vec3 n = normalize(normal);
        float reach = dot(shift, n) + length(n * axes);
        shift += (r - reach) * n;
    }
    for (int k = 0; k < 3; ++k) models[3u * i + uint(k)] = vec4(axes[k], shift[k]);
}
#endif
