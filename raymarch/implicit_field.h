// The colour field along one ray and its first crossing of the surface level.
//
// phi(x) = sum_j v_j W(|x - x_j|, h_j) (DESIGN.md), W the M4 spline. Along a ray
// x(t) = o + t d, particle j contributes f_j(t) = c_j w(q_j(t)) with c_j = v_j / (pi h_j^3),
// q_j = sqrt((t - tc_j)^2 + d2_j) / h_j, tc_j its closest-approach parameter and d2_j its
// squared distance from the ray; it is non-zero only on its support interval (t0_j, t1_j).
//
// The root finder never steps over a crossing. With delta = sqrt(d2) / h, the second
// derivative is exactly f'' = c F(q) / h^2 with
//   F(q) = -3 + 4.5 q - 2.25 delta^2 / q                       for q < 1,
//   F(q) = (2 - q) (1.5 - delta^2 (1.5 + 0.75 q) / q^3)        for 1 <= q < 2,
// increasing on q < 1, and 0 beyond the support. Over a window of the ray, where q_j spans
// [qmin, qmax], it is bounded above by (delta <= q, and 2 - q <= (4 - q^2) / 3 on [1, 2])
//   -0.75 + 2.25 (qmax^2 - delta^2)              when qmax <= 1,
//   1.5 (1 - delta^2 / qmax^2)                   when qmin < 1 < qmax,
//   0.5 (4 - qmin^2) (1 - delta^2 / qmax^2)      when qmin >= 1,
// and below by -3 (q < 1) or -0.75 (q >= 1). With M and m the sums of those bounds,
//   phi(a) + phi'(a) s + m s^2 / 2 <= phi(a + s) <= phi(a) + phi'(a) s + M s^2 / 2.
// The step is the smallest s at which the upper bound reaches the level: it cannot pass the
// first root, it grows far from the surface and it becomes a Newton step from below close to
// it (quadratic convergence). The lower bound proves a crossing: once the two bounds reach
// the level within the tolerance of each other, the first root is bracketed without another
// evaluation. Bounds over a window hold over every part of it, so the steps that converge on
// a root inside the window of the last full sample need phi and phi' only.
//
// Before stepping, the search may jump ahead to a hint (a neighbouring ray's crossing): the
// sum over the particles of each one's largest value on [start, hint] bounds phi there, and
// when it stays below the level no crossing can precede the hint.
#pragma once

#include <cmath>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "core/particles.h"

namespace twinrender::raymarch {

struct Candidate {
    double tc;    // ray parameter of the closest approach to the particle
    double d2;    // squared distance of the particle from the ray line
    double t0;    // support interval (t0, t1) on the ray
    double t1;
    double coef;  // v / (pi h^3)
    double invH;  // 1 / h
    double peak;  // the largest contribution along the ray: coef * w(sqrt(d2) / h)
    std::uint32_t index;
};

// Builds the candidate of a particle at `center` for a ray (origin, unit direction); returns
// false when the ray line misses its support sphere.
bool makeCandidate(const double origin[3], const double direction[3], const double center[3],
                   double h, double volume, std::uint32_t index, Candidate& out);

// What the field build reads of each particle, in one record, float (the field is evaluated
// in float).
struct FieldParticle {
    float x, y, z;
    float support2;  // (2h)^2
    float coef;      // v / (pi h^3)
    float invH2;     // 1 / h^2
};
std::vector<FieldParticle> makeFieldParticles(const core::ParticleSet& particles);

// What a surface point averages over the particles around it (kernel weights).
struct HitAttributes {
    float u, v;     // texture coordinates; u wraps around at 1
    float r, g, b;  // glow
};

// Particles that the fields of several rays are built from (those one bundle gather found),
// in summation order, as float arrays padded to whole vectors with particles that meet no ray.
class ParticleBatch {
public:
    // particles[prims[i]] for each i, and attributes[prims[i]] when given (for average()).
    void assign(std::span<const std::uint32_t> prims, const std::vector<FieldParticle>& particles,
                const HitAttributes* attributes = nullptr);
    std::size_t size() const { return mIndex.size(); }

    // The attributes averaged with one weight per particle of the batch (padding included, 0
    // for those that do not count; `count` of them, padding included), u unwrapped around the
    // heaviest particle's u (the first of equals) so that the seam does not average to 0.5.
    // False when no weight is positive.
    bool average(const float* weights, std::size_t count, HitAttributes& out) const;

private:
    friend class RayField;
    glm::dvec3 mOrigin{0.0};  // the positions are relative to it (the first particle's)
    std::vector<float> mX, mY, mZ, mSupport2, mCoef, mInvH2;
    std::vector<float> mU, mV, mR, mG, mB;
    std::vector<std::uint32_t> mIndex;
};

struct FieldSample {
    double value = 0.0;      // phi(t)
    double slope = 0.0;      // dphi/dt
    double curvature = 0.0;  // M: upper bound of d2phi/dt2 over the window
    double curvatureLow = 0.0;  // m: lower bound of d2phi/dt2 over the window
    double ahead = 0.0;      // upper bound of phi over [t, t + horizon]
};

struct SurfacePoint {
    glm::dvec3 gradient{0.0};  // grad(phi)
    double hMin = 0.0;         // the smallest h of the particles whose support contains it
};

// The candidates of one ray segment in the layout the field loops want: structure of arrays,
// float, ray parameters relative to the segment start, so float keeps about 1e-7 of the
// segment's own scale wherever the segment lies. Particles that do not overlap the segment
// stay as inert candidates (removing them costs more than evaluating them), and the arrays
// are padded with inert ones to a whole number of vectors; the loops run a fixed lane order,
// so results do not depend on the thread that runs them.
class RayField {
public:
    static constexpr std::size_t LANES = 8;

    RayField() = default;
    RayField(const RayField&) = delete;  // its arrays point into its own storage
    RayField& operator=(const RayField&) = delete;

    // `candidates`: in any fixed order (it is the summation order). `base`: a ray parameter
    // near the segment. (A field from candidates built in double, one at a time.)
    void assign(const std::vector<Candidate>& candidates, double base);
    // The field of the ray origin + t direction (unit) on [tMin, tMax] (base = tMin): the
    // particles of `batch` whose support overlaps that interval, in the batch's order. The
    // batch must hold every such particle.
    void build(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax,
               const ParticleBatch& batch);

    // Candidates, the inert ones included (not the padding).
    std::size_t size() const { return mCount; }
    // Candidates whose support overlaps the interval of a build() (the others are inert).
    std::size_t candidates() const { return mCandidates; }
    // Particle index of each candidate.
    const std::uint32_t* indices() const { return mIndex.data(); }
    // The sum of the candidates' peaks: phi stays below it along the whole ray.
    double peakSum() const { return mPeakSum; }
    // Where the first support interval begins (phi = 0 before it); +inf if none. (A pass
    // over the candidates.)
    double supportStart() const;
    // The largest h of the particles whose support reaches past t; 0 if none.
    double largestHBeyond(double t) const;

    // phi, dphi/dt at t, the curvature bounds over [t, t + window] and the bound of phi over
    // [t, t + horizon].
    FieldSample sample(double t, double window, double horizon = 0.0) const;
    // phi and dphi/dt at t only (a third of the work).
    FieldSample sampleValue(double t) const;
    // An upper bound of phi on [t, tEnd]: each particle at its largest value there (its peak
    // when the closest approach lies ahead, its value at t when it lies behind).
    double remainingBound(double t, double tEnd) const;
    // A tighter upper bound of phi on [t, tEnd]: each particle at its largest value there,
    // exactly (at the point of [t, tEnd] closest to it).
    double intervalBound(double t, double tEnd) const;
    // intervalBound over each of the pieces between consecutive points (ascending) at once.
    // Tighter than one bound over the whole: each particle's peak counts only in its own piece.
    static constexpr int PIECES = 3;
    void piecewiseBound(const double (&points)[PIECES + 1], double (&bounds)[PIECES]) const;

    // The kernel weight v_i W(|p - x_i|, h_i) of each candidate at the ray point p(t) into
    // `weights` (0 outside its support; one per candidate, padding included), and grad(phi)
    // there. Needs a field from build().
    SurfacePoint surfacePoint(double t, std::vector<float>& weights) const;

private:
    // Makes room for n candidates (contents undefined) and makes the padding inert.
    void resize(std::size_t n);

    double mBase = 0.0;       // the ray parameter the arrays are relative to
    std::size_t mCount = 0;
    std::size_t mPadded = 0;  // mCount rounded up to LANES
    std::size_t mCandidates = 0;
    double mPeakSum = 0.0;
    // Ray parameters relative to mBase; one allocation, grown as needed and never shrunk.
    std::vector<float> mStore;
    float *mTc = nullptr, *mD2 = nullptr, *mCoef = nullptr,
          *mIh2 = nullptr, *mPeak = nullptr;
    // build(): the ray direction and each particle's offset from its closest-approach point.
    glm::vec3 mDirection{0.0f};
    float *mEx = nullptr, *mEy = nullptr, *mEz = nullptr;
    std::vector<std::uint32_t> mIndex;
};

struct Crossing {
    enum class Status {
        Hit,          // the first crossing is at t (phi(tBelow) < level <= phi(tBelow + tol))
        Miss,         // phi < level on the whole interval
        Inside,       // phi >= level already at the start
        Unresolved,   // iteration limit reached (grazing a tangency): counted, never dropped
    };
    Status status = Status::Miss;
    double t = 0.0;       // the crossing, interpolated inside [tBelow, tBelow + tolerance]
    double tBelow = 0.0;  // the last point known below the level (a safe ray origin)
    int evaluations = 0;
};

struct CrossingSettings {
    double level = 0.13;       // surface level of phi
    double tolerance = 1e-4;   // absolute, along t (the caller passes 1e-4 h)
    double maxStep = 1.0;      // the window over which the curvature bounds are taken
    int maxIterations = 256;
};

// The first t in [ta, tb] where phi reaches the level. `field` must hold every particle whose
// support overlaps [ta, tb] (others may be there too). `hint`, when in (ta, tb), is a guess of
// a point a little before the crossing (a neighbouring ray's): when phi is proven below the
// level on [ta, hint] the search starts there, which skips most of the approach.
Crossing findFirstCrossing(const RayField& field, double ta, double tb,
                           const CrossingSettings& settings, double hint = NAN);

}  // namespace twinrender::raymarch
