#include "compare/flip.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "compare/image_pair.h"
#include "compare/row_kernel.h"
#include "core/error.h"

namespace twinrender::compare {

namespace {

using rowmath::powNonNegative;

// ---- The paper's constants (Andersson et al. 2020, Sections 3-5) --------------------------

// Contrast sensitivity functions in the spatial domain, x in degrees of visual angle:
// S(x) = a1 sqrt(pi / b1) exp(-pi^2 x^2 / b1) + a2 sqrt(pi / b2) exp(-pi^2 x^2 / b2).
// Only blue-yellow has a second Gaussian; a2 = 0 (and b2 unused) for the other two.
struct Csf {
    double a1, b1, a2, b2;
};
constexpr Csf CSF_A = {1.0, 0.0047, 0.0, 1.0e-5};   // achromatic (Y)
constexpr Csf CSF_RG = {1.0, 0.0053, 0.0, 1.0e-5};  // red-green (Cx)
constexpr Csf CSF_BY = {34.1, 0.04, 13.5, 0.025};   // blue-yellow (Cz)

constexpr double qc = 0.7;   // exponent of the HyAB colour distance
constexpr double pc = 0.4;   // fraction of cmax ...
constexpr double pt = 0.95;  // ... that is mapped to this error
constexpr double w = 0.082;  // feature filter width, degrees (std dev = w / 2)
constexpr double qf = 0.5;   // exponent of the feature difference

// ---- Colour spaces ---------------------------------------------------------------------------

using Matrix3 = std::array<std::array<double, 3>, 3>;

// Linear sRGB -> CIE XYZ, derived from the sRGB primaries and the D65 white point.
constexpr Matrix3 RGB_TO_XYZ = {{{0.412386563253, 0.357591490921, 0.180450491204},
                                 {0.212636821677, 0.715182981841, 0.072180196481},
                                 {0.019330620152, 0.119197163640, 0.950372587005}}};

constexpr Matrix3 inverse(const Matrix3& m) {
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    Matrix3 r{};
    r[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
    r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
    r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
    r[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
    r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
    r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
    r[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
    r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
    r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
    return r;
}
constexpr Matrix3 XYZ_TO_RGB = inverse(RGB_TO_XYZ);

// The reference white (Xn, Yn, Zn): XYZ of linear RGB (1, 1, 1).
constexpr std::array<double, 3> WHITE = {RGB_TO_XYZ[0][0] + RGB_TO_XYZ[0][1] + RGB_TO_XYZ[0][2],
                                         RGB_TO_XYZ[1][0] + RGB_TO_XYZ[1][1] + RGB_TO_XYZ[1][2],
                                         RGB_TO_XYZ[2][0] + RGB_TO_XYZ[2][1] + RGB_TO_XYZ[2][2]};

// The transforms in float, as the per-pixel code runs them.
struct ColourConstants {
    float rgbToXyz[3][3];
    float xyzToRgb[3][3];
    float white[3];
    float invWhite[3];
};

constexpr ColourConstants makeColourConstants() {
    ColourConstants k{};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            k.rgbToXyz[i][j] = static_cast<float>(RGB_TO_XYZ[i][j]);
            k.xyzToRgb[i][j] = static_cast<float>(XYZ_TO_RGB[i][j]);
        }
        k.white[i] = static_cast<float>(WHITE[i]);
        k.invWhite[i] = static_cast<float>(1.0 / WHITE[i]);
    }
    return k;
}
constexpr ColourConstants K = makeColourConstants();

struct Vec3 {
    float x, y, z;
};

inline Vec3 mul(const float m[3][3], Vec3 v) {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

// ---- Colour spaces, per pixel ------------------------------------------------------------------

// Display value -> linear RGB (IEC 61966-2-1), after clamping to [0, 1] (NaN -> 0).
inline float srgbToLinear(float v) {
    v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
    // Both branches computed, then selected: loops with a conditional division do not vectorise.
    const float linear = v / 12.92f;
    const float curve = powNonNegative((v + 0.055f) / 1.055f, 2.4f);
    return v <= 0.04045f ? linear : curve;
}

// XYZ -> YCxCz (Section 3.1): the opponent space in which the CSFs are applied; like L*a*b*
// without the cube root.
inline Vec3 xyzToYCxCz(Vec3 xyz) {
    const float x = xyz.x * K.invWhite[0], y = xyz.y * K.invWhite[1], z = xyz.z * K.invWhite[2];
    return {116.0f * y - 16.0f, 500.0f * (x - y), 200.0f * (y - z)};
}

inline Vec3 yCxCzToXyz(Vec3 c) {
    const float y = (c.x + 16.0f) / 116.0f;
    const float x = y + c.y / 500.0f;
    const float z = y - c.z / 200.0f;
    return {x * K.white[0], y * K.white[1], z * K.white[2]};
}

// Cube root of t > 0 to float precision: a first guess from the exponent bits (error < 4 %),
// then two Halley steps in double (4e-2 -> 6e-5 -> 2e-13). Unlike cbrtf, it vectorises.
inline float cbrtPositive(float t) {
    const float guess = std::bit_cast<float>(std::bit_cast<std::uint32_t>(t) / 3u + 709921077u);
    const double x = t;
    double y = guess;
    double y3 = y * y * y;
    y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
    y3 = y * y * y;
    y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
    return static_cast<float>(y);
}

inline float labF(float t) {
    constexpr float delta = 6.0f / 29.0f;
    const float root = cbrtPositive(t > 0.0f ? t : 1.0f);  // both sides computed: no branch
    const float linear = t / (3.0f * delta * delta) + 4.0f / 29.0f;
    return t > delta * delta * delta ? root : linear;
}

// Linear RGB -> CIE L*a*b* with the Hunt adjustment (Section 3.2): a* and b* scaled by
// 0.01 L*, so that dark colours differ less in chroma.
inline Vec3 linearToHuntLab(Vec3 rgb) {
    const Vec3 xyz = mul(K.rgbToXyz, rgb);
    const float fx = labF(xyz.x * K.invWhite[0]);
    const float fy = labF(xyz.y * K.invWhite[1]);
    const float fz = labF(xyz.z * K.invWhite[2]);
    const float L = 116.0f * fy - 16.0f;
    const float hunt = 0.01f * L;
    return {L, hunt * 500.0f * (fx - fy), hunt * 200.0f * (fy - fz)};
}

// HyAB: city-block distance in L, Euclidean in (a, b) (Abasi et al. 2020).
inline float hyab(Vec3 p, Vec3 q) {
    const float da = p.y - q.y, db = p.z - q.z;
    return std::abs(p.x - q.x) + std::sqrt(da * da + db * db);
}

inline Vec3 clamp01(Vec3 v) {
    auto c = [](float f) { return f > 0.0f ? (f < 1.0f ? f : 1.0f) : 0.0f; };
    return {c(v.x), c(v.y), c(v.z)};
}

// ---- Filters ---------------------------------------------------------------------------------

// 1-D factors of the CSF filters (misc/separatedConvolutions.pdf of NVlabs/flip): the
// achromatic and red-green 2-D filters are single Gaussians, each the outer product of a
// normalised 1-D Gaussian with itself. The blue-yellow filter is a sum of two Gaussians,
// g1(x) g1(y) + g2(x) g2(y) with g_i(x) = sqrt(a_i sqrt(pi / b_i)) exp(-pi^2 x^2 / b_i), both
// scaled by one factor so the 2-D filter sums to 1: (sum g1)^2 + (sum g2)^2 = 1.
struct SpatialFilters {
    int radius = 0;
    std::vector<float> y, cx, cz1, cz2;
};

SpatialFilters makeSpatialFilters(double ppd) {
    constexpr double pi = std::numbers::pi;
    const double bMax = std::max({CSF_A.b1, CSF_RG.b1, CSF_BY.b1, CSF_BY.b2});
    SpatialFilters f;
    // Three standard deviations of the widest Gaussian (std dev sqrt(b / (2 pi^2)) degrees).
    f.radius = static_cast<int>(std::ceil(3.0 * std::sqrt(bMax / (2.0 * pi * pi)) * ppd));
    const int n = 2 * f.radius + 1;
    std::vector<double> gy(n), gcx(n), gcz1(n), gcz2(n);
    double sy = 0, scx = 0, scz1 = 0, scz2 = 0;
    for (int i = 0; i < n; ++i) {
        const double x = (i - f.radius) / ppd;  // degrees
        const double x2 = x * x;
        auto g = [&](double a, double b) {
            return a * std::sqrt(pi / b) * std::exp(-pi * pi * x2 / b);
        };
        auto gs = [&](double a, double b) {
            return std::sqrt(a * std::sqrt(pi / b)) * std::exp(-pi * pi * x2 / b);
        };
        sy += gy[i] = g(CSF_A.a1, CSF_A.b1);
        scx += gcx[i] = g(CSF_RG.a1, CSF_RG.b1);
        scz1 += gcz1[i] = gs(CSF_BY.a1, CSF_BY.b1);
        scz2 += gcz2[i] = gs(CSF_BY.a2, CSF_BY.b2);
    }
    const double czNorm = 1.0 / std::sqrt(scz1 * scz1 + scz2 * scz2);
    for (int i = 0; i < n; ++i) {
        f.y.push_back(static_cast<float>(gy[i] / sy));
        f.cx.push_back(static_cast<float>(gcx[i] / scx));
        f.cz1.push_back(static_cast<float>(gcz1[i] * czNorm));
        f.cz2.push_back(static_cast<float>(gcz2[i] * czNorm));
    }
    return f;
}

// Edge and point detectors (Section 4): a Gaussian of std dev sigma = w/2 degrees, its first
// derivative and its second derivative, sampled out to 3 sigma. The Gaussian sums to 1; the
// positive and the negative weights of each derivative sum to +1 and -1.
struct FeatureFilters {
    int radius = 0;
    std::vector<float> g, dg, ddg;
};

FeatureFilters makeFeatureFilters(double ppd) {
    const double sigma = 0.5 * w * ppd;  // pixels
    FeatureFilters f;
    f.radius = static_cast<int>(std::ceil(3.0 * sigma));
    const int n = 2 * f.radius + 1;
    std::vector<double> g(n), dg(n), ddg(n);
    double gSum = 0, dgPos = 0, dgNeg = 0, ddgPos = 0, ddgNeg = 0;
    for (int i = 0; i < n; ++i) {
        const double x = i - f.radius;
        g[i] = std::exp(-x * x / (2.0 * sigma * sigma));
        dg[i] = -x * g[i];
        ddg[i] = (x * x / (sigma * sigma) - 1.0) * g[i];
        gSum += g[i];
        (dg[i] > 0 ? dgPos : dgNeg) += std::abs(dg[i]);
        (ddg[i] > 0 ? ddgPos : ddgNeg) += std::abs(ddg[i]);
    }
    for (int i = 0; i < n; ++i) {
        f.g.push_back(static_cast<float>(g[i] / gSum));
        f.dg.push_back(static_cast<float>(dg[i] / (dg[i] > 0 ? dgPos : dgNeg)));
        f.ddg.push_back(static_cast<float>(ddg[i] / (ddg[i] > 0 ? ddgPos : ddgNeg)));
    }
    return f;
}

// ---- Row kernels ------------------------------------------------------------------------------

// acc[i] += weight * in[i]: one tap of a filter along y.
TWINRENDER_ROW_KERNEL
void accumulateRow(float* __restrict acc, const float* __restrict in, float weight, int n) {
    for (int i = 0; i < n; ++i) acc[i] += weight * in[i];
}

// out[x] = sum_k kernel[k] padded[x + k], x in [0, n): a filter along x, the input padded by
// the kernel radius on both sides.
TWINRENDER_ROW_KERNEL
void convolvePadded(const float* __restrict padded, const float* __restrict kernel, int taps, int n,
                    float* __restrict out) {
    for (int x = 0; x < n; ++x) out[x] = 0.0f;
    for (int k = 0; k < taps; ++k) {
        const float wk = kernel[k];
        const float* __restrict src = padded + k;
        for (int x = 0; x < n; ++x) out[x] += wk * src[x];
    }
}

// Filters one row along x with the clamp-to-edge border: `padded` is scratch.
void filterRow(const std::vector<float>& row, const std::vector<float>& kernel,
               std::vector<float>& padded, float* out) {
    const int width = static_cast<int>(row.size());
    const int radius = static_cast<int>(kernel.size() / 2);
    padded.resize(row.size() + 2 * radius);
    std::fill(padded.begin(), padded.begin() + radius, row.front());
    std::copy(row.begin(), row.end(), padded.begin() + radius);
    std::fill(padded.begin() + radius + width, padded.end(), row.back());
    convolvePadded(padded.data(), kernel.data(), static_cast<int>(kernel.size()), width, out);
}

// Linear RGB in [0, 1] -> YCxCz, and the achromatic channel normalised to [0, 1] (Y / Yn,
// what the feature detectors see).
inline void toYCxCz(Vec3 lin, float& Y, float& Cx, float& Cz, float& luminance) {
    const Vec3 v = xyzToYCxCz(mul(K.rgbToXyz, lin));
    Y = v.x;
    Cx = v.y;
    Cz = v.z;
    luminance = (v.x + 16.0f) / 116.0f;
}

// The linear values of the 256 display values k / 255 an 8-bit file holds (read as
// k * (1 / 255)), by srgbToLinear itself: a row of them is looked up, not computed, to the same
// numbers. The power in srgbToLinear was a quarter of ꟻLIP's time on a PNG pair.
struct EightBitSrgb {
    std::array<float, 256> linear;
    EightBitSrgb() {
        for (int k = 0; k < 256; ++k)
            linear[k] = srgbToLinear(static_cast<float>(k) * (1.0f / 255.0f));
    }
};

inline int eightBitIndex(float v) {
    const float k = v * 255.0f + 0.5f;
    return k > 0.0f ? (k < 255.0f ? static_cast<int>(k) : 255) : 0;  // NaN -> 0
}

// True when each of the n values is k * (1 / 255) for an integer k in [0, 255].
TWINRENDER_ROW_KERNEL
bool isEightBitRow(const float* __restrict v, int n) {
    bool all = true;
    for (int i = 0; i < n; ++i)
        all &= static_cast<float>(eightBitIndex(v[i])) * (1.0f / 255.0f) == v[i];
    return all;
}

// A row of n pixels, R G B interleaved, to YCxCz planes: display sRGB, or linear values
// (`linear`), each loop free of branches so that it vectorises. `eightBit`: the display
// values are all k / 255 (isEightBitRow) and are looked up in it.
TWINRENDER_ROW_KERNEL
void toYCxCzRow(const float* __restrict rgb, int n, bool linear, const EightBitSrgb* eightBit,
                float* __restrict Y, float* __restrict Cx, float* __restrict Cz,
                float* __restrict luminance) {
    if (linear) {
        for (int i = 0; i < n; ++i)
            toYCxCz(clamp01({rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]}), Y[i], Cx[i], Cz[i],
                    luminance[i]);
        return;
    }
    if (eightBit) {
        const float* table = eightBit->linear.data();
        for (int i = 0; i < n; ++i) {
            const Vec3 lin = {table[eightBitIndex(rgb[3 * i])],
                              table[eightBitIndex(rgb[3 * i + 1])],
                              table[eightBitIndex(rgb[3 * i + 2])]};
            toYCxCz(lin, Y[i], Cx[i], Cz[i], luminance[i]);
        }
        return;
    }
    for (int i = 0; i < n; ++i) {
        const Vec3 lin = {srgbToLinear(rgb[3 * i]), srgbToLinear(rgb[3 * i + 1]),
                          srgbToLinear(rgb[3 * i + 2])};
        toYCxCz(lin, Y[i], Cx[i], Cz[i], luminance[i]);
    }
}

struct ColourMapping {
    float cmax;    // HyAB^qc of green against blue: the largest colour distance
    float pccmax;  // pc * cmax
};

// The colour error of one row (Section 3.2) from the CSF-filtered YCxCz of both images (Cz as
// its two separable parts): back to linear RGB, clamped (filtering can leave the gamut),
// Hunt-adjusted L*a*b*, HyAB, ^qc, and [0, pc cmax) -> [0, pt), [pc cmax, cmax] -> [pt, 1].
TWINRENDER_ROW_KERNEL
void colourErrorRow(const float* __restrict refY, const float* __restrict refCx,
                    const float* __restrict refCz1, const float* __restrict refCz2,
                    const float* __restrict testY, const float* __restrict testCx,
                    const float* __restrict testCz1, const float* __restrict testCz2, int n,
                    ColourMapping mapping, float* __restrict out) {
    const float ptF = static_cast<float>(pt);
    const float qcF = static_cast<float>(qc);
    for (int i = 0; i < n; ++i) {
        const Vec3 ref = linearToHuntLab(
            clamp01(mul(K.xyzToRgb, yCxCzToXyz({refY[i], refCx[i], refCz1[i] + refCz2[i]}))));
        const Vec3 test = linearToHuntLab(
            clamp01(mul(K.xyzToRgb, yCxCzToXyz({testY[i], testCx[i], testCz1[i] + testCz2[i]}))));
        const float dE = powNonNegative(hyab(ref, test), qcF);
        const float low = dE * (ptF / mapping.pccmax);
        const float high =
            ptF + (dE - mapping.pccmax) / (mapping.cmax - mapping.pccmax) * (1.0f - ptF);
        out[i] = dE < mapping.pccmax ? low : high;
    }
}

// The FLIP error of one row (Sections 4 and 5): edge and point strengths from the first and
// second derivative responses along x and y, their largest difference / sqrt(2), ^qf, and
// colour error ^ (1 - feature difference). error may alias colourError.
TWINRENDER_ROW_KERNEL
void flipErrorRow(const float* colourError, const float* __restrict refDx,
                  const float* __restrict refDdx, const float* __restrict refDy,
                  const float* __restrict refDdy, const float* __restrict testDx,
                  const float* __restrict testDdx, const float* __restrict testDy,
                  const float* __restrict testDdy, int n, float* error) {
    const float invSqrt2 = static_cast<float>(1.0 / std::numbers::sqrt2);
    static_assert(qf == 0.5, "the feature exponent qf is applied as a square root");
    for (int i = 0; i < n; ++i) {
        const float edgeRef = std::sqrt(refDx[i] * refDx[i] + refDy[i] * refDy[i]);
        const float edgeTest = std::sqrt(testDx[i] * testDx[i] + testDy[i] * testDy[i]);
        const float pointRef = std::sqrt(refDdx[i] * refDdx[i] + refDdy[i] * refDdy[i]);
        const float pointTest = std::sqrt(testDdx[i] * testDdx[i] + testDdy[i] * testDdy[i]);
        const float featureDifference = std::sqrt(
            invSqrt2 * std::max(std::abs(edgeRef - edgeTest), std::abs(pointRef - pointTest)));
        error[i] = powNonNegative(colourError[i], 1.0f - featureDifference);
    }
}

using Row = std::vector<float>;

// The per-row scratch of one thread.
struct RowBuffers {
    // CSF filters, per image: Y, Cx, Cz (first Gaussian), Cz (second Gaussian); along y, then
    // along x.
    std::array<Row, 8> csfVertical, csf;
    // Feature filters, per image: along y by g, dg, ddg; then d/dx, d2/dx2, d/dy, d2/dy2.
    std::array<Row, 6> featureVertical;
    std::array<Row, 8> feature;
    Row padded, error;

    explicit RowBuffers(int width) : error(width) {
        for (auto& r : csfVertical) r.resize(width);
        for (auto& r : csf) r.resize(width);
        for (auto& r : featureVertical) r.resize(width);
        for (auto& r : feature) r.resize(width);
    }
};

}  // namespace

FlipResult flip(const core::Image& reference, const core::Image& test,
                const FlipSettings& settings) {
    requireSameSize("beauty.flip", reference, test);
    if (!(settings.ppd > 0.0) || !std::isfinite(settings.ppd))
        throw std::invalid_argument(
            fmt::format("beauty.flip: ppd (pixels per degree) must be > 0, got {}", settings.ppd));
    core::Image refStorage, testStorage;
    const float* rgb[2] = {rgbPixels(reference, refStorage), rgbPixels(test, testStorage)};
    const int width = reference.width();
    const int height = reference.height();
    const std::size_t n = reference.pixelCount();

    FlipResult result;
    result.errorMap = core::Image(width, height, {"flip"});
    if (n == 0) return result;

    // 1. Both images to YCxCz planes; per image: Y, Cx, Cz, normalised luminance.
    std::array<std::vector<float>, 8> planes;
    for (auto& p : planes) {
        core::reserveHugePages(p, n);
        p.resize(n);
    }
    const bool linear = settings.input == FlipInput::Linear;
    const EightBitSrgb eightBit;
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y) {
            const std::size_t at = static_cast<std::size_t>(y) * width;
            for (int image = 0; image < 2; ++image) {
                const float* row = rgb[image] + 3 * at;
                const bool lookUp = !linear && isEightBitRow(row, 3 * width);
                toYCxCzRow(row, width, linear, lookUp ? &eightBit : nullptr,
                           &planes[4 * image + 0][at], &planes[4 * image + 1][at],
                           &planes[4 * image + 2][at], &planes[4 * image + 3][at]);
            }
        }
    });

    const SpatialFilters csf = makeSpatialFilters(settings.ppd);
    const FeatureFilters feat = makeFeatureFilters(settings.ppd);
    ColourMapping mapping;
    mapping.cmax = static_cast<float>(std::pow(
        hyab(linearToHuntLab({0.0f, 1.0f, 0.0f}), linearToHuntLab({0.0f, 0.0f, 1.0f})), qc));
    mapping.pccmax = static_cast<float>(pc) * mapping.cmax;
    std::vector<double> rowSums(static_cast<std::size_t>(height));

    // 2. Row by row: filter along y, then along x (separable filters commute), colour error,
    // feature difference, FLIP. Rows are independent, so the result does not depend on how
    // they are shared among threads.
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        RowBuffers b(width);
        auto filterAlongY = [&](int y, int radius, auto&& tap) {
            for (int k = 0; k <= 2 * radius; ++k)
                tap(k, static_cast<std::size_t>(std::clamp(y + k - radius, 0, height - 1)) * width);
        };
        for (int y = rows.begin(); y != rows.end(); ++y) {
            // Contrast sensitivity filters (Section 3.1).
            for (auto& r : b.csfVertical) std::fill(r.begin(), r.end(), 0.0f);
            filterAlongY(y, csf.radius, [&](int k, std::size_t at) {
                for (int image = 0; image < 2; ++image) {
                    Row* v = &b.csfVertical[4 * image];
                    const std::vector<float>* p = &planes[4 * image];
                    accumulateRow(v[0].data(), &p[0][at], csf.y[k], width);
                    accumulateRow(v[1].data(), &p[1][at], csf.cx[k], width);
                    accumulateRow(v[2].data(), &p[2][at], csf.cz1[k], width);
                    accumulateRow(v[3].data(), &p[2][at], csf.cz2[k], width);
                }
            });
            for (int image = 0; image < 2; ++image) {
                const Row* v = &b.csfVertical[4 * image];
                Row* out = &b.csf[4 * image];
                filterRow(v[0], csf.y, b.padded, out[0].data());
                filterRow(v[1], csf.cx, b.padded, out[1].data());
                filterRow(v[2], csf.cz1, b.padded, out[2].data());
                filterRow(v[3], csf.cz2, b.padded, out[3].data());
            }
            colourErrorRow(b.csf[0].data(), b.csf[1].data(), b.csf[2].data(), b.csf[3].data(),
                           b.csf[4].data(), b.csf[5].data(), b.csf[6].data(), b.csf[7].data(),
                           width, mapping, b.error.data());

            // Edge and point detection (Section 4) on the unfiltered luminance.
            for (auto& r : b.featureVertical) std::fill(r.begin(), r.end(), 0.0f);
            filterAlongY(y, feat.radius, [&](int k, std::size_t at) {
                for (int image = 0; image < 2; ++image) {
                    Row* v = &b.featureVertical[3 * image];
                    const float* luminance = &planes[4 * image + 3][at];
                    accumulateRow(v[0].data(), luminance, feat.g[k], width);
                    accumulateRow(v[1].data(), luminance, feat.dg[k], width);
                    accumulateRow(v[2].data(), luminance, feat.ddg[k], width);
                }
            });
            for (int image = 0; image < 2; ++image) {
                // d/dx, d2/dx2: derivative along x of the Gaussian along y; d/dy, d2/dy2:
                // Gaussian along x of the derivatives along y.
                const Row* v = &b.featureVertical[3 * image];
                Row* out = &b.feature[4 * image];
                filterRow(v[0], feat.dg, b.padded, out[0].data());
                filterRow(v[0], feat.ddg, b.padded, out[1].data());
                filterRow(v[1], feat.g, b.padded, out[2].data());
                filterRow(v[2], feat.g, b.padded, out[3].data());
            }

            const std::size_t at = static_cast<std::size_t>(y) * width;
            float* error = &result.errorMap.at(at, 0);
            const Row* f = b.feature.data();
            flipErrorRow(b.error.data(), f[0].data(), f[1].data(), f[2].data(), f[3].data(),
                         f[4].data(), f[5].data(), f[6].data(), f[7].data(), width, error);
            double sum = 0.0;
            for (int x = 0; x < width; ++x) sum += error[x];
            rowSums[static_cast<std::size_t>(y)] = sum;
        }
    });

    double total = 0.0;
    for (double s : rowSums) total += s;  // in row order: independent of the thread count
    result.mean = total / static_cast<double>(n);
    return result;
}

}  // namespace twinrender::compare
