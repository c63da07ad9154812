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
//   Var = sum_c (1 / n)^2 sigma_c^2   (sigma_c^2: the variance of y over cell c)
// cannot be estimated from one value per cell. The cells are therefore collapsed into their
// parents of level L - 1, four to a parent p, and the four values of p are taken as four
// independent draws from p: the variance of that coarser design is estimated without bias by
//   V = sum_p (4 / n)^2 s_p^2 / 4,   s_p^2 = sum_{c in p} (y_c - mean_p)^2 / 3,
// i.e. V = sum_p sum_{c in p} (y_c - mean_p)^2 / (12 (n / 4)^2). One sample in each quarter of
// a parent never has more variance than four independent ones in it (stratification with
// proportional allocation), so V is conservative: its expectation is at least the true Var.
// On an occluder's outline (a variance of y that comes from the cells the outline crosses)
// it is about twice Var, twice as many children as parents being cut; inside a region of
// constant y it is 0, which is what lets such a pixel stop early. The standard error is
// sqrt(V); at level 1 it is the textbook s / sqrt(4) of four independent values.
double ProgressiveStrata::standardError() const {
    if (mLevel < 1) return std::numeric_limits<double>::infinity();
    const int side = 1 << mLevel, parentSide = side / 2;
    double squares = 0.0;
    for (int pi = 0; pi < parentSide; ++pi)
        for (int pj = 0; pj < parentSide; ++pj) {
            const double* row0 = &mValues[std::size_t(2 * pi) * side + 2 * pj];
            const double* row1 = row0 + side;
            const double y[4] = {row0[0], row0[1], row1[0], row1[1]};
            const double m = 0.25 * (y[0] + y[1] + y[2] + y[3]);
            for (const double v : y) squares += (v - m) * (v - m);
        }
    const double parents = double(parentSide) * parentSide;
    return std::sqrt(squares / (12.0 * parents * parents));
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
