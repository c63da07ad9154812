#include "raymarch/progressive_strata.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "raymarch/ao_hemisphere.h"

namespace twinrender::raymarch {

const std::vector<glm::dvec2>& ProgressiveStrata::refine() {
    const int level = mLevel + 1;
    const int side = 1 << level;
    // A level's cells jitter by their own hash: (seed, level) taken as one seed of
    // jitteredStratum.
    const std::uint64_t seed = mSeed * 64u + std::uint64_t(level);
    mAdded.clear();
    mAddedCells.clear();
    std::vector<glm::dvec2> points(std::size_t(side) * side);
    std::vector<double> values(points.size(), 0.0);
    if (level == 0) {
        points[0] = jitteredStratum(0, 0, 1, seed);
        mAdded.push_back(points[0]);
        mAddedCells.push_back(0);
    }
    const int parentSide = side / 2;
    for (int pi = 0; pi < parentSide; ++pi)
        for (int pj = 0; pj < parentSide; ++pj) {
            const glm::dvec2 kept = mPoints[std::size_t(pi) * parentSide + pj];
            // The child the kept point lies in (clamped: a point at 1 - ulp rounds up).
            const int ki = std::clamp(int(kept.x * side), 2 * pi, 2 * pi + 1);
            const int kj = std::clamp(int(kept.y * side), 2 * pj, 2 * pj + 1);
            for (int i = 2 * pi; i < 2 * pi + 2; ++i)
                for (int j = 2 * pj; j < 2 * pj + 2; ++j) {
                    const int cell = i * side + j;
                    if (i == ki && j == kj) {
                        points[cell] = kept;
                        values[cell] = mValues[std::size_t(pi) * parentSide + pj];
                        continue;
                    }
                    points[cell] = jitteredStratum(i, j, side, seed);
                    mAdded.push_back(points[cell]);
                    mAddedCells.push_back(cell);
                }
        }
    mPoints.swap(points);
    mValues.swap(values);
    mLevel = level;
    return mAdded;
}

void ProgressiveStrata::record(const double* values) {
    for (std::size_t k = 0; k < mAddedCells.size(); ++k) mValues[mAddedCells[k]] = values[k];
}

double ProgressiveStrata::mean() const {
    double sum = 0.0;
    for (const double v : mValues) sum += v;
    return mValues.empty() ? 0.0 : sum / double(mValues.size());
}

// The estimate at level L is the mean of n = 4^L values y_c, one per cell c, each point
// uniform in its cell: a stratified estimator with one sample per stratum, whose variance
//   Var = sum_c sigma_c^2 / n^2   (sigma_c^2: the variance of y over cell c)
// cannot be estimated from one value per cell without assuming something of how y varies
// between cells. Two textbook estimates are taken, and the larger:
// - collapsed strata (Cochran, "Sampling Techniques", 5A.12): the cells are collapsed into
//   their parents of level L - 1, four to a parent p, whose four values are taken as four
//   independent draws from p. That coarser design's variance is estimated without bias by
//     V_p = sum_p (4 / n)^2 s_p^2 / 4,  s_p^2 = sum_{c in p} (y_c - mean_p)^2 / 3,
//   and one point in each quarter of a parent never has more variance than four independent
//   ones in it (proportional stratification), so V_p is conservative: its expectation is at
//   least Var. On an outline (the variance of y comes from the cells it crosses) it is about
//   twice Var, twice as many children as parents being cut.
// - successive differences (Wolter, "Introduction to Variance Estimation", 8.2): each value
//   against its neighbours in the grid, V_d = mean over adjacent pairs of (y_c - y_c')^2 / 2,
//   divided by n. It sees what V_p cannot: an outline that runs between parents, each parent
//   on one side of it (a straight edge across the sun's disc along the grid), leaves every
//   parent uniform and V_p = 0, while the neighbours across it differ.
// Inside a region of constant y both are 0, which is what lets such a pixel stop early; a
// feature smaller than the cells that no point met is invisible to both. The standard error
// is sqrt(max(V_p, V_d)); at level 1, V_p is the textbook s^2 / 4 of four independent values.
double ProgressiveStrata::standardError() const {
    if (mLevel < 1) return std::numeric_limits<double>::infinity();
    const int side = 1 << mLevel, parentSide = side / 2;
    const auto y = [&](int i, int j) { return mValues[std::size_t(i) * side + j]; };
    double squares = 0.0;
    for (int pi = 0; pi < parentSide; ++pi)
        for (int pj = 0; pj < parentSide; ++pj) {
            const double four[4] = {y(2 * pi, 2 * pj), y(2 * pi, 2 * pj + 1), y(2 * pi + 1, 2 * pj),
                                    y(2 * pi + 1, 2 * pj + 1)};
            const double m = 0.25 * (four[0] + four[1] + four[2] + four[3]);
            for (const double v : four) squares += (v - m) * (v - m);
        }
    const double parents = double(parentSide) * parentSide;
    const double collapsed = squares / (12.0 * parents * parents);
    double differences = 0.0;
    for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j) {
            if (i + 1 < side) differences += (y(i, j) - y(i + 1, j)) * (y(i, j) - y(i + 1, j));
            if (j + 1 < side) differences += (y(i, j) - y(i, j + 1)) * (y(i, j) - y(i, j + 1));
        }
    const double n = double(side) * side, pairs = 2.0 * side * (side - 1);
    const double successive = differences / (2.0 * pairs * n);
    return std::sqrt(std::max(collapsed, successive));
}

bool roundsDone(const ProgressiveStrata& strata, const RoundLimits& limits) {
    return strata.level() >= limits.lastLevel ||
           (strata.level() >= limits.firstLevel && strata.standardError() < limits.target);
}

bool stoppedAtCap(const ProgressiveStrata& strata, const RoundLimits& limits) {
    return strata.level() >= limits.lastLevel && !(strata.standardError() < limits.target);
}

RoundLimits roundLimits(double target, int samples) {
    RoundLimits limits{.target = target, .lastLevel = 0};
    while ((std::int64_t(4) << (2 * limits.lastLevel)) <= std::int64_t(CAP_MULTIPLE) * samples)
        ++limits.lastLevel;
    limits.firstLevel = std::min(limits.firstLevel, limits.lastLevel);
    return limits;
}

}  // namespace twinrender::raymarch
