#include "raymarch/progressive_strata.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>

namespace twinrender::raymarch {
namespace {

// Fills `strata` up to `level`, each point's value f(point); returns every point, in the order
// refine() gave them.
template <typename F>
std::vector<glm::dvec2> fill(ProgressiveStrata& strata, int level, F&& f) {
    std::vector<glm::dvec2> all;
    while (strata.level() < level) {
        const std::vector<glm::dvec2> points = strata.refine();
        std::vector<double> values;
        for (const glm::dvec2& p : points) values.push_back(f(p));
        strata.record(values.data());
        all.insert(all.end(), points.begin(), points.end());
    }
    return all;
}

TEST(ProgressiveStrata, EveryLevelHasOnePointInEachCellAndKeepsTheLevelBefore) {
    ProgressiveStrata strata(17);
    std::vector<glm::dvec2> all;
    for (int level = 0; level <= 4; ++level) {
        const std::vector<glm::dvec2> added = strata.refine();
        EXPECT_EQ(added.size(), level == 0 ? 1u : 3u << (2 * (level - 1))) << level;
        std::vector<double> zeros(added.size(), 0.0);
        strata.record(zeros.data());
        all.insert(all.end(), added.begin(), added.end());
        ASSERT_EQ(all.size(), std::size_t(1) << (2 * level));
        const int side = 1 << level;
        std::set<std::pair<int, int>> cells;
        for (const glm::dvec2& p : all) {
            ASSERT_GE(p.x, 0.0);
            ASSERT_LT(p.x, 1.0);
            ASSERT_GE(p.y, 0.0);
            ASSERT_LT(p.y, 1.0);
            cells.insert({int(p.x * side), int(p.y * side)});
        }
        EXPECT_EQ(cells.size(), all.size()) << "level " << level;
        EXPECT_EQ(strata.points(), int(all.size()));
    }
}

TEST(ProgressiveStrata, TheSameSeedGivesTheSamePoints) {
    ProgressiveStrata a(5), b(5), c(6);
    const auto one = [](glm::dvec2) { return 1.0; };
    const auto pa = fill(a, 3, one), pb = fill(b, 3, one), pc = fill(c, 3, one);
    EXPECT_EQ(pa, pb);
    EXPECT_NE(pa, pc);
}

TEST(ProgressiveStrata, AConstantHasNoErrorAndTheFirstLevelHasNoEstimate) {
    ProgressiveStrata strata(3);
    fill(strata, 0, [](glm::dvec2) { return 0.7; });
    EXPECT_TRUE(std::isinf(strata.standardError()));
    fill(strata, 2, [](glm::dvec2) { return 0.7; });
    EXPECT_DOUBLE_EQ(strata.mean(), 0.7);
    EXPECT_EQ(strata.standardError(), 0.0);
}

TEST(ProgressiveStrata, AtTheFirstLevelTheErrorIsThatOfFourIndependentValues) {
    ProgressiveStrata strata(9);
    int k = 0;
    const double y[4] = {1.0, 0.0, 0.0, 1.0};
    fill(strata, 1, [&](glm::dvec2) { return y[k++]; });
    // The values in refine's order; s^2 = sum (y - 0.5)^2 / 3 = 1 / 3, s / sqrt(4).
    EXPECT_DOUBLE_EQ(strata.mean(), 0.5);
    EXPECT_DOUBLE_EQ(strata.standardError(), std::sqrt(1.0 / 3.0) / 2.0);
}

TEST(ProgressiveStrata, AnEdgeBetweenParentsStillHasAnError) {
    // 1 on the half x < 0.5: every parent of level 1 lies on one side, so their four values
    // agree and the collapsed strata see no spread; the neighbours across the edge differ.
    ProgressiveStrata strata(4);
    fill(strata, 2, [](glm::dvec2 p) { return p.x < 0.5 ? 1.0 : 0.0; });
    EXPECT_DOUBLE_EQ(strata.mean(), 0.5);
    // 4 of the 24 adjacent pairs differ: sqrt(4 / (2 x 24) / 16).
    EXPECT_DOUBLE_EQ(strata.standardError(), std::sqrt(4.0 / 48.0 / 16.0));
}

// A disc of the unit square, 1 inside (an occluder's outline across the strata): over many
// seeds the estimate is unbiased, and its stated standard error is not smaller than its true
// spread (the collapsed strata overstate the variance, by about 2 on an outline), nor many
// times larger.
TEST(ProgressiveStrata, TheStandardErrorBoundsTheTrueSpreadOfAnOutline) {
    const glm::dvec2 centre(0.43, 0.57);
    const double radius = 0.31, area = M_PI * radius * radius;
    const auto disc = [&](glm::dvec2 p) {
        return glm::dot(p - centre, p - centre) < radius * radius ? 1.0 : 0.0;
    };
    for (const int level : {2, 3, 4}) {
        const int runs = 2000;
        double sum = 0.0, squares = 0.0, stated = 0.0;
        for (int seed = 0; seed < runs; ++seed) {
            ProgressiveStrata strata(std::uint64_t(seed) * 7919u + std::uint64_t(level));
            fill(strata, level, disc);
            const double e = strata.mean() - area;
            sum += e;
            squares += e * e;
            stated += strata.standardError() * strata.standardError();
        }
        const double bias = sum / runs, spread = std::sqrt(squares / runs);
        const double statedRms = std::sqrt(stated / runs);
        // The mean of 2000 runs: within 4 of its own standard errors.
        EXPECT_LT(std::abs(bias), 4.0 * spread / std::sqrt(double(runs))) << level;
        // The spread's estimate from 2000 runs is good to a few percent.
        EXPECT_GT(statedRms, 1.1 * spread) << level;
        EXPECT_LT(statedRms, 2.5 * spread) << level;
    }
}

TEST(ProgressiveStrata, RoundsStopBelowTheTargetOrAtTheCap) {
    // The cap: the largest power of 4 not above 4 x the fixed count.
    const RoundLimits limits = roundLimits(0.02, 64);
    EXPECT_EQ(limits.firstLevel, 2);
    EXPECT_EQ(limits.lastLevel, 4);  // 256 points
    EXPECT_EQ(roundLimits(0.02, 36).lastLevel, 3);
    EXPECT_EQ(roundLimits(0.02, 4096).lastLevel, 7);
    EXPECT_EQ(roundLimits(0.02, 1).lastLevel, 1);
    EXPECT_EQ(roundLimits(0.02, 1).firstLevel, 1);
    // A step across the square (an outline) takes rounds until its error is below the
    // target; a constant stops at the first level tested, 16 points.
    const auto step = [](glm::dvec2 p) { return p.x + 0.6 * p.y < 0.8 ? 1.0 : 0.0; };
    int belowCap = 0;
    for (const double target : {0.05, 0.03, 0.02, 0.01}) {
        const RoundLimits l = roundLimits(target, 256);
        for (std::uint64_t seed = 0; seed < 200; ++seed) {
            ProgressiveStrata strata(seed);
            int rounds = 0;
            sampleInRounds(strata, l, [&](const std::vector<glm::dvec2>& points, double* y) {
                ++rounds;
                for (std::size_t j = 0; j < points.size(); ++j) y[j] = step(points[j]);
            });
            ASSERT_EQ(rounds, strata.level() + 1);
            ASSERT_GE(strata.level(), l.firstLevel);
            if (strata.level() < l.lastLevel) {
                ++belowCap;
                EXPECT_LT(strata.standardError(), target) << target << " " << seed;
            }
        }
    }
    EXPECT_GT(belowCap, 600);
    ProgressiveStrata constant(1);
    sampleInRounds(constant, roundLimits(1e-9, 1024),
                   [](const std::vector<glm::dvec2>& points, double* y) {
                       for (std::size_t j = 0; j < points.size(); ++j) y[j] = 0.25;
                   });
    EXPECT_EQ(constant.points(), 16);
    EXPECT_EQ(constant.mean(), 0.25);
}

}  // namespace
}  // namespace twinrender::raymarch
