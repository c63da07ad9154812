// A pixel's secondary rays taken in rounds until its estimate is good enough
// (raymarch.ao_error, emissive_error, sun_error): the points of the unit square that the
// direction maps (ao_hemisphere.h, emitter_cone.h, sun_disc.h) lift onto the sphere, a level
// at a time, and the stratified estimate over them with its standard error.
//
// Level L holds one point in each cell of the 2^L x 2^L grid. A round keeps every point of
// the level before and adds one in each of the three cells of a parent's four that its point
// left empty, jittered inside the cell: the progressive jittered construction of Christensen,
// Kensler and Kilpatrick, "Progressive Multi-Jittered Sample Sequences" (EGSR 2018). The old
// point is uniform in the child it fell in, so every level is a jittered stratified pattern
// with the distribution of ao_hemisphere.h's side x side one (side 2^L): no ray is wasted and
// the estimator stays stratified at every level.
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <vector>

namespace twinrender::raymarch {

class ProgressiveStrata {
  public:
    // Points jittered by hashes of (seed, level, cell): the same for a given seed on every
    // thread count.
    explicit ProgressiveStrata(std::uint64_t seed) : mSeed(seed) {}

    // The next level's new points, in the order record() takes their values: the first point
    // (level 0), then three per cell of the level before.
    const std::vector<glm::dvec2>& refine();
    // The values of the points refine() last returned, in that order.
    void record(const double* values);

    // The level the recorded points fill (4^level points); -1 before the first round.
    int level() const { return mLevel; }
    int points() const { return static_cast<int>(mValues.size()); }
    // The stratified estimate: the mean of the values, each cell weighing 1 / 4^level.
    double mean() const;
    // The standard error of mean(), +inf at level 0 (one point says nothing of the spread).
    double standardError() const;

  private:
    std::uint64_t mSeed;
    int mLevel = -1;
    std::vector<glm::dvec2> mPoints;  // one per cell of the level, in rows of 2^level
    std::vector<double> mValues;
    std::vector<glm::dvec2> mAdded;  // the last round's new points ...
    std::vector<int> mAddedCells;    // ... and their cells
};

// How a pixel's rounds stop (the settings raymarch.*_error and *_samples).
struct RoundLimits {
    double target = 0.0;  // standard error to reach, > 0
    int firstLevel = 2;   // the level whose error is first tested (16 points)
    int lastLevel = 3;    // the cap: the level taken whatever its error
};

// The levels of a target's rounds for a fixed count of `samples`: the first tested is 2
// (16 points; 4 would judge the spread from 4 values) and the cap the largest power of 4 not
// above CAP_MULTIPLE x samples: 256 points for 64, and always more than `samples`, so that
// the pixels whose variance is high get more rays than the fixed count gives them.
RoundLimits roundLimits(double target, int samples);
inline constexpr int CAP_MULTIPLE = 4;

// Whether the rounds of `strata` are over: its standard error is below limits.target (tested
// from level limits.firstLevel on), or level limits.lastLevel is filled.
bool roundsDone(const ProgressiveStrata& strata, const RoundLimits& limits);
// Whether they stopped at the cap with the error at the target or above it.
bool stoppedAtCap(const ProgressiveStrata& strata, const RoundLimits& limits);

// Rounds of `strata` until roundsDone. trace(points, values) fills the value of each new
// point; the caller keeps whatever else a point's ray gave (a colour) in the same order.
template <typename Trace>
void sampleInRounds(ProgressiveStrata& strata, const RoundLimits& limits, Trace&& trace) {
    std::vector<double> values;
    do {
        const std::vector<glm::dvec2>& points = strata.refine();
        values.assign(points.size(), 0.0);
        trace(points, values.data());
        strata.record(values.data());
    } while (!roundsDone(strata, limits));
}

}  // namespace twinrender::raymarch
