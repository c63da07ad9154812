#include "compare/temporal_error.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/frame.h"

namespace twinrender::compare {
namespace {

// An AOV image covered in columns [x0, x1) with normal (sin a, 0, cos a), beauty grey g there.
core::Image aov(int x0, int x1, double angleDeg, float grey) {
    core::Image im = core::aov::makeImage(16, 8);
    const double a = angleDeg * M_PI / 180.0;
    for (int y = 0; y < im.height(); ++y)
        for (int x = x0; x < x1; ++x) {
            for (const char* c : {"R", "G", "B"}) im.at(x, y, im.channelIndex(c)) = grey;
            im.at(x, y, im.channelIndex("A")) = 1.0f;
            im.at(x, y, im.channelIndex("N.X")) = float(std::sin(a));
            im.at(x, y, im.channelIndex("N.Z")) = float(std::cos(a));
        }
    return im;
}

core::Image display(const core::Image& aovImage) {
    return aovImage.select(std::vector<std::string>{"R", "G", "B"});
}

TEST(TemporalError, MotionBothRenderersShowIsNotFlicker) {
    // The surface moves two pixels; both renderers show the same images.
    const core::Image a = aov(2, 8, 0.0, 0.6f), b = aov(4, 10, 0.0, 0.6f);
    const core::Image da = display(a), db = display(b);
    const FrameChange c = frameChange({a, da}, {b, db}, {a, da}, {b, db}, {});
    EXPECT_GT(c.realtimeFlip, 0.05);  // the motion is a visible change
    EXPECT_DOUBLE_EQ(c.flicker(), 0.0);
    EXPECT_DOUBLE_EQ(c.normalFlickerDeg(), 0.0);
    EXPECT_EQ(c.normalPixels, 4u * 8u);  // columns 4..7 covered in both frames
}

TEST(TemporalError, AChangeOnlyTheRealTimeFramesHaveIsFlicker) {
    // The reference stands still; the real-time normals turn by 10 degrees and its shade
    // changes.
    const core::Image ref = aov(2, 10, 0.0, 0.6f), test0 = aov(2, 10, 0.0, 0.6f),
                      test1 = aov(2, 10, 10.0, 0.4f);
    const core::Image dr = display(ref), d0 = display(test0), d1 = display(test1);
    const FrameChange c = frameChange({ref, dr}, {ref, dr}, {test0, d0}, {test1, d1}, {});
    EXPECT_EQ(c.referenceFlip, 0.0);
    EXPECT_GT(c.flicker(), 0.05);
    EXPECT_NEAR(c.realtimeNormalDeg, 10.0, 1e-4);  // float normals
    EXPECT_NEAR(c.normalFlickerDeg(), 10.0, 1e-4);
    MetricValues m;
    addFrameChangeMetrics(c, m);
    EXPECT_DOUBLE_EQ(m.at("temporal.flicker"), c.flicker());
    EXPECT_DOUBLE_EQ(m.at("temporal.normal_flicker_deg"), c.normalFlickerDeg());
    EXPECT_EQ(m.size(), 6u);
}

TEST(TemporalError, NoCommonCoverageGivesNoNormalChange) {
    const core::Image a = aov(0, 4, 0.0, 0.5f), b = aov(8, 12, 0.0, 0.5f);
    const core::Image da = display(a), db = display(b);
    const FrameChange c = frameChange({a, da}, {b, db}, {a, da}, {b, db}, {});
    EXPECT_EQ(c.normalPixels, 0u);
    EXPECT_TRUE(std::isnan(c.normalFlickerDeg()));
    const core::Image small = core::aov::makeImage(8, 8);
    EXPECT_THROW(frameChange({a, da}, {small, display(small)}, {a, da}, {b, db}, {}),
                 core::NotComparableError);
}

}  // namespace
}  // namespace twinrender::compare
