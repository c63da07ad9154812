#include "compare/temporal_error.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace twinrender::compare {

namespace {

// Coverage above half a pixel counts as covered (A is 0 or 1 in both renderers' AOVs).
constexpr float COVERED = 0.5f;

bool hasNormals(const core::Image& image) {
    return image.hasChannel("A") && image.hasChannel("N.X") && image.hasChannel("N.Y") &&
           image.hasChannel("N.Z");
}

double angleDeg(const core::Image& a, const core::Image& b, std::size_t p) {
    const int ax = a.channelIndex("N.X"), bx = b.channelIndex("N.X");
    double dot = 0.0, la = 0.0, lb = 0.0;
    for (int c = 0; c < 3; ++c) {
        const double u = a.at(p, ax + c), v = b.at(p, bx + c);
        dot += u * v;
        la += u * u;
        lb += v * v;
    }
    const double d = la > 0.0 && lb > 0.0 ? dot / std::sqrt(la * lb) : 1.0;
    return std::acos(std::clamp(d, -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace

FrameChange frameChange(const FrameImages& previousReference, const FrameImages& reference,
                        const FrameImages& previousTest, const FrameImages& test,
                        const FlipSettings& flipSettings) {
    FrameChange c;
    c.realtimeFlip = flip(previousTest.display, test.display, flipSettings).mean;
    c.referenceFlip = flip(previousReference.display, reference.display, flipSettings).mean;
    const core::Image* images[] = {&previousReference.aov, &reference.aov, &previousTest.aov,
                                   &test.aov};
    for (const core::Image* im : images)
        if (im->width() != test.aov.width() || im->height() != test.aov.height())
            throw core::NotComparableError(
                fmt::format("frames of {}x{} and {}x{} pixels: a sequence keeps its size",
                            im->width(), im->height(), test.aov.width(), test.aov.height()));
    if (!std::all_of(std::begin(images), std::end(images),
                     [](auto* im) { return hasNormals(*im); })) {
        c.realtimeNormalDeg = c.referenceNormalDeg = NAN;
        return c;
    }
    double sumTest = 0.0, sumRef = 0.0;
    for (std::size_t p = 0; p < test.aov.pixelCount(); ++p) {
        bool covered = true;
        for (const core::Image* im : images)
            covered = covered && im->at(p, im->channelIndex("A")) > COVERED;
        if (!covered) continue;
        sumTest += angleDeg(previousTest.aov, test.aov, p);
        sumRef += angleDeg(previousReference.aov, reference.aov, p);
        ++c.normalPixels;
    }
    const double n = static_cast<double>(c.normalPixels);
    c.realtimeNormalDeg = n > 0 ? sumTest / n : NAN;
    c.referenceNormalDeg = n > 0 ? sumRef / n : NAN;
    return c;
}

void addFrameChangeMetrics(const FrameChange& change, MetricValues& metrics) {
    metrics["temporal.frame_flip"] = change.realtimeFlip;
    metrics["temporal.reference_frame_flip"] = change.referenceFlip;
    metrics["temporal.flicker"] = change.flicker();
    metrics["temporal.normal_change_deg"] = change.realtimeNormalDeg;
    metrics["temporal.reference_normal_change_deg"] = change.referenceNormalDeg;
    metrics["temporal.normal_flicker_deg"] = change.normalFlickerDeg();
}

}  // namespace twinrender::compare
