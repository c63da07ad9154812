#include "compare/buffer_metrics.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "compare/distance_transform.h"
#include "compare/image_pair.h"
#include "core/error.h"

namespace twinrender::compare {

namespace {

constexpr double NOT_A_NUMBER = std::numeric_limits<double>::quiet_NaN();
constexpr double INF = std::numeric_limits<double>::infinity();
constexpr double DEGREES_PER_RADIAN = 180.0 / 3.14159265358979323846;
// The angle given to a zero-length normal (see angleDeg).
constexpr double UNKNOWN_DIRECTION_DEG = 90.0;
constexpr double NORMAL_QUANTILE = 0.95;  // normal.p95_deg

void requireComparable(const core::Image& reference, const core::Image& test, const Masks& masks,
                       const char* metric) {
    if (reference.width() != test.width() || reference.height() != test.height())
        throw core::NotComparableError(fmt::format(
            "{}: the reference is {}x{} pixels but the test is {}x{}; render both at the same "
            "camera.width and camera.height",
            metric, reference.width(), reference.height(), test.width(), test.height()));
    if (masks.coveredInBoth.width() != reference.width() ||
        masks.coveredInBoth.height() != reference.height())
        throw std::invalid_argument(fmt::format(
            "{}: the masks are {}x{} but the images {}x{}", metric, masks.coveredInBoth.width(),
            masks.coveredInBoth.height(), reference.width(), reference.height()));
}

// Channel indices of the same names in both images; a missing one throws NotComparableError
// naming the metric, the image and the channel.
template <std::size_t N>
struct ChannelPair {
    std::array<int, N> ref;
    std::array<int, N> test;
};

template <std::size_t N>
ChannelPair<N> requireChannels(const core::Image& reference, const core::Image& test,
                               const std::array<const char*, N>& names, const char* metric) {
    ChannelPair<N> c;
    for (std::size_t i = 0; i < N; ++i) {
        const int r = reference.channelIndex(names[i]);
        const int t = test.channelIndex(names[i]);
        if (r < 0 || t < 0)
            throw core::NotComparableError(fmt::format("{}: the {} image has no channel \"{}\"",
                                                       metric, r < 0 ? "reference" : "test",
                                                       names[i]));
        c.ref[i] = r;
        c.test[i] = t;
    }
    return c;
}

// Runs f(y, sums) for every row in parallel, each row into its own N sums, and adds the rows
// in order: the same result for any number of threads.
template <std::size_t N, typename F>
std::array<double, N> sumRows(int height, F&& f) {
    std::vector<std::array<double, N>> rows(static_cast<std::size_t>(height));
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& r) {
        for (int y = r.begin(); y != r.end(); ++y) {
            std::array<double, N> s{};
            f(y, s);
            rows[static_cast<std::size_t>(y)] = s;
        }
    });
    std::array<double, N> total{};
    for (const auto& s : rows)
        for (std::size_t i = 0; i < N; ++i) total[i] += s[i];
    return total;
}

double ratioOrNaN(double numerator, double count) {
    return count > 0.0 ? numerator / count : NOT_A_NUMBER;
}

}  // namespace

// ---- coverage.iou -------------------------------------------------------------------------

double coverageIou(const Masks& masks) {
    const Mask& r = masks.referenceCovered;
    const Mask& t = masks.testCovered;
    if (r.pixelCount() == 0) return NOT_A_NUMBER;
    std::size_t both = 0, either = 0;
    for (std::size_t p = 0; p < r.pixelCount(); ++p) {
        both += r[p] && t[p];
        either += r[p] || t[p];
    }
    return either == 0 ? 1.0 : static_cast<double>(both) / static_cast<double>(either);
}

// ---- silhouette.mean_px -------------------------------------------------------------------

Mask outlineMask(const Mask& covered) {
    const int w = covered.width();
    const int h = covered.height();
    Mask outline(w, h);
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < w; ++x) {
                if (!covered(x, y)) continue;
                outline.set(x, y,
                            (x > 0 && !covered(x - 1, y)) || (x + 1 < w && !covered(x + 1, y)) ||
                                (y > 0 && !covered(x, y - 1)) || (y + 1 < h && !covered(x, y + 1)));
            }
    });
    return outline;
}

double silhouetteMeanPx(const Masks& masks) {
    const Mask refOutline = outlineMask(masks.referenceCovered);
    const Mask testOutline = outlineMask(masks.testCovered);
    const std::size_t nRef = refOutline.count();
    const std::size_t nTest = testOutline.count();
    if (nRef == 0 && nTest == 0) return NOT_A_NUMBER;
    if (nRef == 0 || nTest == 0) return INF;
    const std::vector<float> toTest = squaredDistanceTransform(testOutline);
    const std::vector<float> toRef = squaredDistanceTransform(refOutline);
    const int w = refOutline.width();
    const auto sums = sumRows<1>(refOutline.height(), [&](int y, std::array<double, 1>& s) {
        const std::size_t row = static_cast<std::size_t>(y) * w;
        for (int x = 0; x < w; ++x) {
            const std::size_t p = row + x;
            if (refOutline[p]) s[0] += std::sqrt(static_cast<double>(toTest[p]));
            if (testOutline[p]) s[0] += std::sqrt(static_cast<double>(toRef[p]));
        }
    });
    return sums[0] / static_cast<double>(nRef + nTest);
}

// ---- depth.rel_mean -----------------------------------------------------------------------

DepthResult depthError(const core::Image& reference, const core::Image& test, const Masks& masks) {
    requireComparable(reference, test, masks, "depth.rel_mean");
    const auto c = requireChannels<1>(reference, test, {"Z"}, "depth.rel_mean");
    const int w = reference.width();
    DepthResult result;
    result.errorMap = core::Image(w, reference.height(), {"relative_error"});
    const auto sums = sumRows<2>(reference.height(), [&](int y, std::array<double, 2>& s) {
        for (int x = 0; x < w; ++x) {
            // Same body only: where the visible bodies differ the depths belong to different
            // surfaces (a near rock against a planet 1e9 away) and one such pixel would
            // outweigh the rest; those pixels are occlusion-order errors, id.mismatch.
            if (!masks.sameBody(x, y)) continue;
            const double zr = reference.at(x, y, c.ref[0]);
            const double zt = test.at(x, y, c.test[0]);
            const double e = std::abs(zt - zr) / zr;
            result.errorMap.at(x, y, 0) = static_cast<float>(e);
            s[0] += e;
            s[1] += 1.0;
        }
    });
    result.relMean = ratioOrNaN(sums[0], sums[1]);
    return result;
}

// ---- id.mismatch --------------------------------------------------------------------------

IdResult idMismatch(const core::Image& reference, const core::Image& test, const Masks& masks) {
    requireComparable(reference, test, masks, "id.mismatch");
    const auto c = requireChannels<1>(reference, test, {"id"}, "id.mismatch");
    const int w = reference.width();
    IdResult result;
    result.errorMap = core::Image(w, reference.height(), {"mismatch"});
    const auto sums = sumRows<2>(reference.height(), [&](int y, std::array<double, 2>& s) {
        for (int x = 0; x < w; ++x) {
            if (!masks.coveredInBoth(x, y)) continue;
            const bool differs = reference.at(x, y, c.ref[0]) != test.at(x, y, c.test[0]);
            result.errorMap.at(x, y, 0) = differs ? 1.0f : 0.0f;
            s[0] += differs;
            s[1] += 1.0;
        }
    });
    result.mismatch = ratioOrNaN(sums[0], sums[1]);
    return result;
}

// ---- normal.mean_deg, normal.p95_deg ------------------------------------------------------

double angleDeg(double ax, double ay, double az, double bx, double by, double bz) {
    const double cx = ay * bz - az * by;
    const double cy = az * bx - ax * bz;
    const double cz = ax * by - ay * bx;
    const double dot = ax * bx + ay * by + az * bz;
    if ((ax == 0.0 && ay == 0.0 && az == 0.0) || (bx == 0.0 && by == 0.0 && bz == 0.0))
        return UNKNOWN_DIRECTION_DEG;
    return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), dot) * DEGREES_PER_RADIAN;
}

double quantile(std::vector<double>& values, double q) {
    if (values.empty()) return NOT_A_NUMBER;
    if (!(q >= 0.0 && q <= 1.0))
        throw std::invalid_argument(fmt::format("quantile: q must be in [0, 1], got {}", q));
    const double position = q * static_cast<double>(values.size() - 1);
    const std::size_t lo = static_cast<std::size_t>(std::floor(position));
    std::nth_element(values.begin(), values.begin() + lo, values.end());
    const double low = values[lo];
    if (lo + 1 >= values.size()) return low;
    // After nth_element every element past lo is >= values[lo]: the next order statistic is
    // their minimum.
    const double high = *std::min_element(values.begin() + lo + 1, values.end());
    return low + (position - static_cast<double>(lo)) * (high - low);
}

NormalResult normalError(const core::Image& reference, const core::Image& test,
                         const Masks& masks) {
    requireComparable(reference, test, masks, "normal.mean_deg");
    const auto c = requireChannels<3>(reference, test, {"N.X", "N.Y", "N.Z"}, "normal.mean_deg");
    const int w = reference.width();
    const int h = reference.height();
    NormalResult result;
    result.errorMap = core::Image(w, h, {"angle_deg"});
    // Angles in double for the pooled values (the map is float).
    std::vector<double> angles(reference.pixelCount(), 0.0);
    const auto sums = sumRows<2>(h, [&](int y, std::array<double, 2>& s) {
        for (int x = 0; x < w; ++x) {
            if (!masks.coveredInBoth(x, y)) continue;
            const double a = angleDeg(reference.at(x, y, c.ref[0]), reference.at(x, y, c.ref[1]),
                                      reference.at(x, y, c.ref[2]), test.at(x, y, c.test[0]),
                                      test.at(x, y, c.test[1]), test.at(x, y, c.test[2]));
            result.errorMap.at(x, y, 0) = static_cast<float>(a);
            const std::size_t p = static_cast<std::size_t>(y) * w + x;
            angles[p] = a;
            if (masks.interior[p]) {
                s[0] += a;
                s[1] += 1.0;
            }
        }
    });
    result.meanDeg = ratioOrNaN(sums[0], sums[1]);
    std::vector<double> pooled;
    pooled.reserve(static_cast<std::size_t>(sums[1]));
    for (std::size_t p = 0; p < angles.size(); ++p)
        if (masks.interior[p]) pooled.push_back(angles[p]);
    result.p95Deg = quantile(pooled, NORMAL_QUANTILE);
    return result;
}

// ---- uv.mean ------------------------------------------------------------------------------

double uvDistance(double uRef, double vRef, double uTest, double vTest) {
    // u is periodic with period 1: the shorter way round. fmod keeps values written slightly
    // outside [0, 1) (a blur across the seam) on the circle.
    double du = std::fmod(std::abs(uTest - uRef), 1.0);
    du = std::min(du, 1.0 - du);
    const double dv = vTest - vRef;
    return std::sqrt(du * du + dv * dv);
}

UvResult uvError(const core::Image& reference, const core::Image& test, const Masks& masks) {
    requireComparable(reference, test, masks, "uv.mean");
    const auto c = requireChannels<2>(reference, test, {"uv.U", "uv.V"}, "uv.mean");
    const int w = reference.width();
    UvResult result;
    result.errorMap = core::Image(w, reference.height(), {"uv_error"});
    const auto sums = sumRows<2>(reference.height(), [&](int y, std::array<double, 2>& s) {
        for (int x = 0; x < w; ++x) {
            if (!masks.coveredInBoth(x, y)) continue;
            const double e = uvDistance(reference.at(x, y, c.ref[0]), reference.at(x, y, c.ref[1]),
                                        test.at(x, y, c.test[0]), test.at(x, y, c.test[1]));
            result.errorMap.at(x, y, 0) = static_cast<float>(e);
            if (masks.interior(x, y)) {
                s[0] += e;
                s[1] += 1.0;
            }
        }
    });
    result.mean = ratioOrNaN(sums[0], sums[1]);
    return result;
}

// ---- emission.rmse ------------------------------------------------------------------------

EmissionResult emissionError(const core::Image& reference, const core::Image& test,
                             const Masks& masks) {
    requireComparable(reference, test, masks, "emission.rmse");
    const auto c = requireChannels<3>(reference, test, {"emission.R", "emission.G", "emission.B"},
                                      "emission.rmse");
    const int w = reference.width();
    EmissionResult result;
    result.errorMap = core::Image(w, reference.height(), {"rmse"});
    const auto sums = sumRows<2>(reference.height(), [&](int y, std::array<double, 2>& s) {
        for (int x = 0; x < w; ++x) {
            if (!masks.coveredInBoth(x, y)) continue;
            double squared = 0.0;
            for (int k = 0; k < 3; ++k) {
                const double d = static_cast<double>(test.at(x, y, c.test[k])) -
                                 static_cast<double>(reference.at(x, y, c.ref[k]));
                squared += d * d;
            }
            result.errorMap.at(x, y, 0) = static_cast<float>(std::sqrt(squared / 3.0));
            s[0] += squared;
            s[1] += 3.0;
        }
    });
    result.rmse = sums[1] > 0.0 ? std::sqrt(sums[0] / sums[1]) : NOT_A_NUMBER;
    return result;
}

// ---- flux.ratio ---------------------------------------------------------------------------

double fluxRatio(const core::Image& reference, const core::Image& test) {
    requireSameSize("flux.ratio", reference, test);
    const auto c = requireChannels<3>(reference, test, {"R", "G", "B"}, "flux.ratio");
    const int w = reference.width();
    const auto sums = sumRows<2>(reference.height(), [&](int y, std::array<double, 2>& s) {
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < 3; ++k) {
                s[0] += static_cast<double>(reference.at(x, y, c.ref[k]));
                s[1] += static_cast<double>(test.at(x, y, c.test[k]));
            }
    });
    return sums[0] != 0.0 ? sums[1] / sums[0] : NOT_A_NUMBER;
}

// ---- smoothness.ratio ---------------------------------------------------------------------

SmoothnessResult smoothness(const core::Image& reference, const core::Image& test,
                            const Masks& masks) {
    requireComparable(reference, test, masks, "smoothness.ratio");
    const auto c = requireChannels<3>(reference, test, {"N.X", "N.Y", "N.Z"}, "smoothness.ratio");
    const int w = reference.width();
    const int h = reference.height();
    const Mask& in = masks.interior;
    auto angle = [](const core::Image& img, const std::array<int, 3>& n, std::size_t p,
                    std::size_t q) {
        return angleDeg(img.at(p, n[0]), img.at(p, n[1]), img.at(p, n[2]), img.at(q, n[0]),
                        img.at(q, n[1]), img.at(q, n[2]));
    };
    // Each edge between interior 4-neighbours once: to the right and downward, per field. An
    // edge serves both its pixels, so each angle is computed once, not twice.
    const std::size_t n = reference.pixelCount();
    std::vector<float> rightRef(n), rightTest(n), downRef(n), downTest(n);
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t p = static_cast<std::size_t>(y) * w + x;
                if (!in[p]) continue;
                if (x + 1 < w && in[p + 1]) {
                    rightRef[p] = static_cast<float>(angle(reference, c.ref, p, p + 1));
                    rightTest[p] = static_cast<float>(angle(test, c.test, p, p + 1));
                }
                if (y + 1 < h && in[p + w]) {
                    downRef[p] = static_cast<float>(angle(reference, c.ref, p, p + w));
                    downTest[p] = static_cast<float>(angle(test, c.test, p, p + w));
                }
            }
    });
    const auto sums = sumRows<3>(h, [&](int y, std::array<double, 3>& s) {
        if (y == 0 || y + 1 == h) return;
        for (int x = 1; x + 1 < w; ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * w + x;
            if (!(in[p] && in[p - 1] && in[p + 1] && in[p - w] && in[p + w])) continue;
            s[0] +=
                (static_cast<double>(rightRef[p]) + rightRef[p - 1] + downRef[p] + downRef[p - w]) /
                4.0;
            s[1] += (static_cast<double>(rightTest[p]) + rightTest[p - 1] + downTest[p] +
                     downTest[p - w]) /
                    4.0;
            s[2] += 1.0;
        }
    });
    SmoothnessResult result;
    result.pixels = static_cast<std::size_t>(sums[2]);
    result.referenceRoughnessDeg = ratioOrNaN(sums[0], sums[2]);
    result.testRoughnessDeg = ratioOrNaN(sums[1], sums[2]);
    if (result.pixels == 0)
        result.ratio = NOT_A_NUMBER;
    else if (result.referenceRoughnessDeg > 0.0)
        result.ratio = result.testRoughnessDeg / result.referenceRoughnessDeg;
    else
        result.ratio = result.testRoughnessDeg > 0.0 ? INF : 1.0;
    return result;
}

// ---- shadow -------------------------------------------------------------------------------

ShadowResult shadowError(const core::Image& reference, const core::Image& test,
                         const Masks& masks) {
    requireComparable(reference, test, masks, "shadow.iou");
    const auto c = requireChannels<1>(reference, test, {"shadow"}, "shadow.iou");
    const int w = reference.width();
    ShadowResult result;
    result.errorMap = core::Image(w, reference.height(), {"disagreement"});
    // Counts: pixels, shadowed in both, shadowed in either, false shadow, missed shadow, leaks;
    // the sum of the absolute visibility errors.
    const auto sums = sumRows<7>(reference.height(), [&](int y, std::array<double, 7>& s) {
        for (int x = 0; x < w; ++x) {
            if (!masks.facingLight(x, y)) continue;
            const float refVisibility = reference.at(x, y, c.ref[0]);
            const float testVisibility = test.at(x, y, c.test[0]);
            const bool refShadowed = refVisibility < SHADOWED_BELOW;
            const bool testShadowed = testVisibility < SHADOWED_BELOW;
            s[0] += 1.0;
            s[5] += refVisibility <= 0.0f && !testShadowed;
            s[6] += std::abs(double(testVisibility) - double(refVisibility));
            s[1] += refShadowed && testShadowed;
            s[2] += refShadowed || testShadowed;
            if (testShadowed && !refShadowed) {
                s[3] += 1.0;
                result.errorMap.at(x, y, 0) = SHADOW_FALSE;
            } else if (refShadowed && !testShadowed) {
                s[4] += 1.0;
                result.errorMap.at(x, y, 0) = SHADOW_MISSED;
            }
        }
    });
    if (sums[0] == 0.0) {
        result.iou = result.falseShadow = result.missedShadow = NOT_A_NUMBER;
        result.mae = result.leak = NOT_A_NUMBER;
        return result;
    }
    result.iou = sums[2] > 0.0 ? sums[1] / sums[2] : 1.0;
    result.falseShadow = sums[3] / sums[0];
    result.missedShadow = sums[4] / sums[0];
    result.leak = sums[5] / sums[0];
    result.mae = sums[6] / sums[0];
    return result;
}

// ---- ao ------------------------------------------------------------------------------------

Mask depthEdgeMask(const core::Image& reference, const Mask& covered) {
    const int w = reference.width(), h = reference.height();
    const int z = reference.requireChannel("Z"), id = reference.requireChannel("id");
    Mask edges(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!covered(x, y)) continue;
            const float depth = reference.at(x, y, z), body = reference.at(x, y, id);
            bool edge = false;
            for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                const int nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                edge = edge || !covered(nx, ny) || reference.at(nx, ny, id) != body ||
                       std::abs(double(reference.at(nx, ny, z)) - double(depth)) >
                           AO_DEPTH_EDGE * double(depth);
            }
            edges.set(x, y, edge);
        }
    return edges;
}

namespace {

// AoResult::grain and banding.
void aoNoise(const core::Image& reference, const core::Image& test, const Masks& masks,
             int refChannel, int testChannel, AoResult& result) {
    const int w = reference.width(), h = reference.height(), r = AO_NOISE_WINDOW / 2;
    const auto index = [w](int x, int y) { return static_cast<std::size_t>(y) * w + x; };
    std::vector<double> error(static_cast<std::size_t>(w) * h, 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (masks.interior(x, y))
                error[index(x, y)] =
                    double(test.at(x, y, testChannel)) - reference.at(x, y, refChannel);
    // The local mean over the interior pixels of each window, then the two parts' sums.
    std::vector<double> local(error.size(), 0.0);
    double n = 0.0, grain = 0.0, sum = 0.0, square = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!masks.interior(x, y)) continue;
            double s = 0.0, count = 0.0;
            for (int v = std::max(0, y - r); v <= std::min(h - 1, y + r); ++v)
                for (int u = std::max(0, x - r); u <= std::min(w - 1, x + r); ++u)
                    if (masks.interior(u, v)) {
                        s += error[index(u, v)];
                        count += 1.0;
                    }
            const double mean = s / count;
            local[index(x, y)] = mean;
            const double rest = error[index(x, y)] - mean;
            grain += rest * rest;
            sum += mean;
            square += mean * mean;
            n += 1.0;
        }
    if (n == 0.0) {
        result.grain = result.banding = NOT_A_NUMBER;
        return;
    }
    result.grain = std::sqrt(grain / n);
    result.banding = std::sqrt(std::max(square / n - (sum / n) * (sum / n), 0.0));
}

}  // namespace

AoResult aoError(const core::Image& reference, const core::Image& test, const Masks& masks) {
    requireComparable(reference, test, masks, "ao.mean_abs");
    const auto c = requireChannels<1>(reference, test, {"ao"}, "ao.mean_abs");
    const int w = reference.width();
    const std::vector<float> toEdge =
        squaredDistanceTransform(depthEdgeMask(reference, masks.referenceCovered));
    AoResult result;
    result.errorMap = core::Image(w, reference.height(), {"abs_error"});
    // Pixels, |error| sum, error sum; halo pixels, their |error| sum; open pixels, the
    // occlusion added there; the occluded pixels' occlusion, the part of it missed.
    const auto sums = sumRows<9>(reference.height(), [&](int y, std::array<double, 9>& s) {
        for (int x = 0; x < w; ++x) {
            if (!masks.coveredInBoth(x, y)) continue;
            const double ref = reference.at(x, y, c.ref[0]);
            const double error = double(test.at(x, y, c.test[0])) - ref;
            result.errorMap.at(x, y, 0) = static_cast<float>(std::abs(error));
            s[0] += 1.0;
            s[1] += std::abs(error);
            s[2] += error;
            if (toEdge[static_cast<std::size_t>(y) * w + x] <= float(AO_HALO_PX * AO_HALO_PX)) {
                s[3] += 1.0;
                s[4] += std::abs(error);
            }
            if (ref >= AO_OPEN) {
                s[5] += 1.0;
                s[6] += std::max(-error, 0.0);
            } else if (ref < AO_OCCLUDED) {
                s[7] += 1.0 - ref;
                s[8] += std::clamp(error, 0.0, 1.0 - ref);
            }
        }
    });
    result.meanAbs = ratioOrNaN(sums[1], sums[0]);
    result.bias = ratioOrNaN(sums[2], sums[0]);
    result.halo = ratioOrNaN(sums[4], sums[3]);
    result.falseOcclusion = ratioOrNaN(sums[6], sums[5]);
    result.missed = ratioOrNaN(sums[8], sums[7]);
    aoNoise(reference, test, masks, c.ref[0], c.test[0], result);
    return result;
}

namespace {

// The irradiance's luminance at a pixel (Rec. 709 weights), of channels c, c + 1, c + 2.
double irradianceLuminance(const core::Image& image, int x, int y, int c) {
    return 0.2126 * image.at(x, y, c) + 0.7152 * image.at(x, y, c + 1) +
           0.0722 * image.at(x, y, c + 2);
}

// Whether either image has a non-zero value in the three channels from `first` anywhere.
bool hasAnyOf(const core::Image& reference, const core::Image& test, const char* first) {
    for (const core::Image* image : {&reference, &test}) {
        if (!image->hasChannel(first)) continue;
        const int c = image->channelIndex(first);
        for (std::size_t p = 0; p < image->pixelCount(); ++p)
            for (int k = 0; k < 3; ++k)
                if (image->at(p, c + k) != 0.0f) return true;
    }
    return false;
}

}  // namespace

bool hasIrradiance(const core::Image& reference, const core::Image& test) {
    return hasAnyOf(reference, test, "irradiance.R");
}

bool hasInscatter(const core::Image& reference, const core::Image& test) {
    return hasAnyOf(reference, test, "inscatter.R");
}

InscatterResult inscatterError(const core::Image& reference, const core::Image& test) {
    if (reference.width() != test.width() || reference.height() != test.height())
        throw core::NotComparableError(fmt::format("inscatter.rmse: the images are {}x{} and {}x{}",
                                                   reference.width(), reference.height(),
                                                   test.width(), test.height()));
    const auto c = requireChannels<1>(reference, test, {"inscatter.R"}, "inscatter.rmse");
    const int w = reference.width(), h = reference.height();
    InscatterResult result;
    result.errorMap = core::Image(w, h, {"abs_error"});
    // Pixels, squared error sum, squared reference sum.
    const auto sums = sumRows<3>(h, [&](int y, std::array<double, 3>& s) {
        for (int x = 0; x < w; ++x) {
            const double ref = irradianceLuminance(reference, x, y, c.ref[0]);
            const double tst = irradianceLuminance(test, x, y, c.test[0]);
            if (ref == 0.0 && tst == 0.0) continue;
            const double error = tst - ref;
            result.errorMap.at(x, y, 0) = static_cast<float>(std::abs(error));
            s[0] += 1.0;
            s[1] += error * error;
            s[2] += ref * ref;
        }
    });
    result.rmse = sums[0] > 0.0 ? std::sqrt(sums[1] / sums[0]) : NOT_A_NUMBER;
    result.rel = sums[2] > 0.0 ? std::sqrt(sums[1] / sums[2]) : NOT_A_NUMBER;
    return result;
}

IndirectResult indirectError(const core::Image& reference, const core::Image& test,
                             const Masks& masks) {
    requireComparable(reference, test, masks, "indirect.rmse");
    const auto c = requireChannels<1>(reference, test, {"irradiance.R"}, "indirect.rmse");
    const int w = reference.width(), h = reference.height();
    IndirectResult result;
    result.errorMap = core::Image(w, h, {"abs_error"});
    // The threshold: a fraction of the reference's 99th percentile over the pixels covered in
    // both (a percentile, so that a few bright pixels next to an emitter do not set it).
    std::vector<double> lit;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (masks.coveredInBoth(x, y))
                lit.push_back(irradianceLuminance(reference, x, y, c.ref[0]));
    if (lit.empty()) {
        result.rmse = result.missed = result.falseLight = NOT_A_NUMBER;
        return result;
    }
    const auto rank = lit.begin() + static_cast<std::ptrdiff_t>(0.99 * double(lit.size() - 1));
    std::nth_element(lit.begin(), rank, lit.end());
    result.threshold = INDIRECT_LIT_FRACTION * *rank;
    const double tau = result.threshold;
    // Pixels, squared error sum; lit in the reference, of them dark in the test; dark in the
    // reference, of them lit in the test.
    const auto sums = sumRows<6>(h, [&](int y, std::array<double, 6>& s) {
        for (int x = 0; x < w; ++x) {
            if (!masks.coveredInBoth(x, y)) continue;
            const double ref = irradianceLuminance(reference, x, y, c.ref[0]);
            const double tst = irradianceLuminance(test, x, y, c.test[0]);
            const double error = tst - ref;
            result.errorMap.at(x, y, 0) = static_cast<float>(std::abs(error));
            s[0] += 1.0;
            s[1] += error * error;
            // tau = 0 (no light in the reference): every pixel is dark in it.
            const bool refLit = tau > 0.0 && ref >= tau,
                       testLit = tau > 0.0 ? tst >= tau : tst > 0.0;
            if (refLit) {
                s[2] += 1.0;
                s[3] += testLit ? 0.0 : 1.0;
            } else {
                s[4] += 1.0;
                s[5] += testLit ? 1.0 : 0.0;
            }
        }
    });
    result.rmse = std::sqrt(sums[1] / sums[0]);
    result.missed = ratioOrNaN(sums[3], sums[2]);
    result.falseLight = ratioOrNaN(sums[5], sums[4]);
    return result;
}

}  // namespace twinrender::compare
