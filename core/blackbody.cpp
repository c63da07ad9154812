#include "core/blackbody.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace twinrender::core {

namespace {

// Integration grid: 380..780 nm in 2 nm steps, composite Simpson (201 nodes). The narrowest
// lobe of the fit below has sigma = 11.8 nm, so the quadrature error is far below the fit's.
constexpr double LAMBDA_MIN_NM = 380.0;
constexpr double LAMBDA_MAX_NM = 780.0;
constexpr int INTERVALS = 200;  // even, for Simpson
constexpr double STEP_NM = (LAMBDA_MAX_NM - LAMBDA_MIN_NM) / INTERVALS;

// Planck's law constants (CODATA 2018, exact in SI).
constexpr double PLANCK_H = 6.62607015e-34;   // J s
constexpr double LIGHT_C = 299792458.0;       // m / s
constexpr double BOLTZMANN_K = 1.380649e-23;  // J / K
constexpr double C2 = PLANCK_H * LIGHT_C / BOLTZMANN_K;  // second radiation constant, m K

constexpr double REFERENCE_KELVIN = 1500.0;  // glow has luminance 1 at this temperature

// Wyman, Sloan & Shirley, "Simple Analytic Approximations to the CIE XYZ Color Matching
// Functions", JCGT 2(2), 2013: the multi-lobe fit, a sum of piecewise Gaussians
// g(lambda; mu, sigma1, sigma2) with sigma1 below mu and sigma2 above.
double g(double lambda, double mu, double sigma1, double sigma2) {
    const double t = (lambda - mu) / (lambda < mu ? sigma1 : sigma2);
    return std::exp(-0.5 * t * t);
}
double xBar(double l) {
    return 1.056 * g(l, 599.8, 37.9, 31.0) + 0.362 * g(l, 442.0, 16.0, 26.7) -
           0.065 * g(l, 501.1, 20.4, 26.2);
}
double yBar(double l) { return 0.821 * g(l, 568.8, 46.9, 40.5) + 0.286 * g(l, 530.9, 16.3, 31.1); }
double zBar(double l) { return 1.217 * g(l, 437.0, 11.8, 36.0) + 0.681 * g(l, 459.0, 26.0, 13.8); }

struct CmfTable {
    // Simpson weight times the colour-matching functions at each node.
    std::array<double, INTERVALS + 1> wx{}, wy{}, wz{};
    std::array<double, INTERVALS + 1> lambdaM{};  // wavelength, m
};

CmfTable makeTable() {
    CmfTable t;
    for (int i = 0; i <= INTERVALS; ++i) {
        const double l = LAMBDA_MIN_NM + STEP_NM * i;
        const double w = (i == 0 || i == INTERVALS) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        t.wx[i] = w * xBar(l);
        t.wy[i] = w * yBar(l);
        t.wz[i] = w * zBar(l);
        t.lambdaM[i] = l * 1e-9;
    }
    return t;
}

// Spectral radiance up to the constant 2 h c^2 and the Simpson step (which the normalisation
// to 1500 K removes), integrated against x̄ ȳ z̄.
void planckXyz(double kelvin, double& x, double& y, double& z) {
    static const CmfTable table = makeTable();
    x = y = z = 0.0;
    for (int i = 0; i <= INTERVALS; ++i) {
        const double l = table.lambdaM[i];
        const double l5 = l * l * l * l * l;
        // 1 / (l^5 (exp(c2 / (l T)) - 1)); expm1 overflows to inf at low T, giving 0.
        const double b = 1.0 / (l5 * std::expm1(C2 / (l * kelvin)));
        x += b * table.wx[i];
        y += b * table.wy[i];
        z += b * table.wz[i];
    }
}

// CIE XYZ -> linear sRGB (IEC 61966-2-1, D65 white).
glm::dvec3 xyzToLinearSrgb(double x, double y, double z) {
    return {3.2404542 * x - 1.5371385 * y - 0.4985314 * z,
            -0.9692660 * x + 1.8760108 * y + 0.0415560 * z,
            0.0556434 * x - 0.2040259 * y + 1.0572252 * z};
}

// Luminance of a linear sRGB colour (the Y row of sRGB -> XYZ).
double luminance(const glm::dvec3& rgb) {
    return 0.2126729 * rgb.r + 0.7151522 * rgb.g + 0.0721750 * rgb.b;
}

glm::dvec3 unscaledRgb(double kelvin) {
    double x, y, z;
    planckXyz(kelvin, x, y, z);
    const glm::dvec3 rgb = xyzToLinearSrgb(x, y, z);
    return {std::max(rgb.r, 0.0), std::max(rgb.g, 0.0), std::max(rgb.b, 0.0)};
}

}  // namespace

// The normalisation applies to the returned (clamped) colour: its luminance is exactly 1 at
// 1500 K. The clamp matters there: the Planckian locus at 1500 K lies just outside the sRGB
// gamut (blue < 0), so the XYZ luminance before clamping is about 1 % lower.
glm::vec3 blackbodyRadiance(double kelvin) {
    if (!(kelvin > 0.0) || !std::isfinite(kelvin)) return glm::vec3(0.0f);
    static const double scale = 1.0 / luminance(unscaledRgb(REFERENCE_KELVIN));
    return glm::vec3(unscaledRgb(kelvin) * scale);
}

}  // namespace twinrender::core
