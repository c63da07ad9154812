// The filtered shadow maps' visibility (shadows = "esm", "vsm", "evsm"): the map written by
// shadow_moments.frag and blurred by shadow_blur.frag, read with one bilinear tap at tc, against
// the receiver's normalised light depth t (bias included). Uniforms set by the shade pass:
uniform vec2 uExponents;      // ESM: c, 0; EVSM: c+, c- (per unit of normalised depth)
uniform float uBleedReduction;  // VSM, EVSM: Chebyshev bounds below this count as 0, [0, 1)

// The variance's floor, in normalised depth squared: d^2 - d d in 32 bits loses about 1e-7 of
// d^2 to cancellation, which would make a lit flat receiver flicker.
const float VSM_MIN_VARIANCE = 1e-5;

// Chebyshev's one-sided upper bound on the share of the filtered region nearer the light than
// t, from the mean and mean square of its depths, with light-bleed reduction: values below
// uBleedReduction become 0 and the rest are rescaled to [0, 1].
float chebyshevUpperBound(vec2 moments, float t, float minVariance) {
    if (t <= moments.x) return 1.0;
    float variance = max(moments.y - moments.x * moments.x, minVariance);
    float d = t - moments.x;
    float p = variance / (variance + d * d);
    return clamp((p - uBleedReduction) / (1.0 - uBleedReduction), 0.0, 1.0);
}

float filteredVisibility(sampler2D map, vec2 tc, float t) {
    vec4 m = textureLod(map, tc, 0.0);
#if defined(SHADOWS_ESM) && defined(ESM_SEED)
    // The seed's form: the exponential of the blurred depth.
    return clamp(exp(uExponents.x * (m.x - t)), 0.0, 1.0);
#elif defined(SHADOWS_ESM)
    // The filtered exp(c d) times exp(-c t): both factors stay inside a 32-bit float.
    return clamp(m.x * exp(-uExponents.x * t), 0.0, 1.0);
#elif defined(SHADOWS_VSM)
    return chebyshevUpperBound(m.xy, t, VSM_MIN_VARIANCE);
#else  // SHADOWS_EVSM
    // Each warp's variance floor scaled by the warp's slope at t, as the depths' spread is.
    float positive = exp(uExponents.x * t);
    float negative = -exp(-uExponents.y * t);
    float slopePositive = uExponents.x * positive;
    float slopeNegative = uExponents.y * negative;
    float p = chebyshevUpperBound(m.xy, positive, VSM_MIN_VARIANCE * slopePositive * slopePositive);
    float n = chebyshevUpperBound(m.zw, negative, VSM_MIN_VARIANCE * slopeNegative * slopeNegative);
    return min(p, n);
#endif
}
