#include "core/blackbody.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace twinrender::core {

namespace {

// Integration grid: Simpson's rule on 201 nodes evenly spaced in wavenumber nu = 1/lambda
// between 1/780 and 1/380 nm^-1 (steps of 0.9 nm at 380 nm to 3.8 nm at 780 nm; the narrowest
// lobe of the fit, sigma = 11.8 nm, sits at 437 nm). Even in nu the Planck factors
// exp(c2 nu / T) form a geometric sequence: one exp per temperature instead of one per node,
// which matters for files with a temperature per particle. Agrees with a 2 nm grid in
// wavelength to 1e-4 (relative, per channel) from 1000 K to 30000 K.
constexpr double LAMBDA_MIN_NM = 380.0;
constexpr double LAMBDA_MAX_NM = 780.0;
constexpr int INTERVALS = 200;                  // even, for Simpson
constexpr double NU_MIN = 1.0 / LAMBDA_MAX_NM;  // nm^-1
constexpr double NU_MAX = 1.0 / LAMBDA_MIN_NM;
constexpr double NU_STEP = (NU_MAX - NU_MIN) / INTERVALS;

// Planck's law constants (CODATA 2018, exact in SI).
constexpr double PLANCK_H = 6.62607015e-34;                       // J s
constexpr double LIGHT_C = 299792458.0;                           // m / s
constexpr double BOLTZMANN_K = 1.380649e-23;                      // J / K
constexpr double C2_NM = PLANCK_H * LIGHT_C / BOLTZMANN_K * 1e9;  // second radiation constant, nm K

constexpr double REFERENCE_KELVIN = 1500.0;  // glow has luminance 1 at this temperature

// Wyman, Sloan & Shirley, "Simple Analytic Approximations to the CIE XYZ Color Matching
// Functions", JCGT 2(2), 2013: the multi-lobe fit, a sum of piecewise Gaussians
// g(lambda; mu, sigma1, sigma2) with sigma1 below mu and sigma2 above (lambda in nm).
double g(double lambda, double mu, double sigma1, double sigma2) {
    const double t = (lambda - mu) / (lambda < mu ? sigma1 : sigma2);
    return std::exp(-0.5 * t * t);
}
double xBar(double l) {
    return 1.056 * g(l, 599.8, 37.9, 31.0) + 0.362 * g(l, 442.0, 16.0, 26.7) -
           0.065 * g(l, 501.1, 20.4, 26.2);
}
double yBar(double l) {
    return 0.821 * g(l, 568.8, 46.9, 40.5) + 0.286 * g(l, 530.9, 16.3, 31.1);
}
double zBar(double l) {
    return 1.217 * g(l, 437.0, 11.8, 36.0) + 0.681 * g(l, 459.0, 26.0, 13.8);
}

// Planck's spectral radiance per wavelength, B = 2 h c^2 lambda^-5 / (exp(c2 / (lambda T)) - 1),
// integrated over lambda = 1/nu (d lambda = d nu / nu^2): nu^3 / (exp(c2 nu / T) - 1) d nu, up
// to constants that the normalisation to 1500 K removes. The table holds, per node, the
// Simpson weight times nu^3 times the colour-matching functions.
struct CmfTable {
    std::array<double, INTERVALS + 1> wx{}, wy{}, wz{};
};

CmfTable makeTable() {
    CmfTable t;
    for (int i = 0; i <= INTERVALS; ++i) {
        const double nu = NU_MIN + NU_STEP * i;
        const double l = 1.0 / nu;
        const double w = ((i == 0 || i == INTERVALS) ? 1.0 : (i % 2 ? 4.0 : 2.0)) * nu * nu * nu;
        t.wx[i] = w * xBar(l);
        t.wy[i] = w * yBar(l);
        t.wz[i] = w * zBar(l);
    }
    return t;
}

void planckXyz(double kelvin, double& x, double& y, double& z) {
    static const CmfTable table = makeTable();
    x = y = z = 0.0;
    // e = exp(c2 nu_i / T), a geometric sequence in i; at low T it overflows to inf and the
    // terms become 0, as they should.
    double e = std::exp(C2_NM * NU_MIN / kelvin);
    const double ratio = std::exp(C2_NM * NU_STEP / kelvin);
    for (int i = 0; i <= INTERVALS; ++i, e *= ratio) {
        const double b = 1.0 / (e - 1.0);
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
// gamut (blue = -0.066 Y), so the XYZ luminance before clamping is 0.5 % lower.
glm::vec3 blackbodyRadiance(double kelvin) {
    if (!(kelvin > 0.0) || !std::isfinite(kelvin)) return glm::vec3(0.0f);
    static const double scale = 1.0 / luminance(unscaledRgb(REFERENCE_KELVIN));
    return glm::vec3(unscaledRgb(kelvin) * scale);
}

}  // namespace twinrender::core
