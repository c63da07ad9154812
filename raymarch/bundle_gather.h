// Gathering support spheres for a bundle of nearly parallel rays with one Embree traversal.
//
// Gathering per ray costs one Embree callback per sphere crossed (~70 per ray near a
// surface). Neighbouring pixels cross almost the same spheres, so a bundle of up to 64 rays
// (a pixel block, or the shadow rays of one) is gathered at once: an Embree user geometry
// holds the particles, in groups of neighbours, with their support spheres (radius 2h)
// inflated by a margin, the bundle's central ray is traced through it, and the callback tests
// each member's real support sphere against every ray of the bundle over that ray's own
// interval. The result is exact as long as every
// ray of the bundle stays within the margin of the central ray near the spheres it crosses;
// the caller guarantees it. The same scene answers first-entry queries along lines.
#pragma once

#include <embree3/rtcore.h>

#include <cmath>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "raymarch/embree_device.h"

namespace twinrender::raymarch {

struct RayBundle {
    static constexpr int MAX_RAYS = 64;
    static constexpr int LANES = 8;  // the test runs this many rays at a time
    int count = 0;
    // Per ray, in float: the test only selects spheres; the field build tests them again.
    float ox[MAX_RAYS], oy[MAX_RAYS], oz[MAX_RAYS];
    float dx[MAX_RAYS], dy[MAX_RAYS], dz[MAX_RAYS];
    float tMin[MAX_RAYS], tMax[MAX_RAYS];  // the interval of each ray to gather over

    // Appends a ray.
    void add(const glm::dvec3& origin, const glm::dvec3& direction, double t0, double t1);
    // Pads to whole vectors with rays that overlap nothing; call before gathering.
    void finish();
};

// Relative slack of the float sphere tests: they may report a sphere that only grazes a ray
// (the field build tests it again), never miss one.
constexpr float GATHER_SLACK = 1e-4f;

// Whether the ray o + t d (float, as RayBundle holds it) meets the support sphere of centre c
// and radius r over [tMin, tMax]: the test a gather applies to each ray of its bundle, and
// SphereSet::select to each sphere of its set, so that both select the same spheres.
inline int rayMeetsSupport(float cx, float cy, float cz, float r, float ox, float oy, float oz,
                           float dx, float dy, float dz, float tMin, float tMax) {
    const float r2 = r * r * (1.0f + 2.0f * GATHER_SLACK);
    const float slack = r * GATHER_SLACK;
    const float wx = cx - ox, wy = cy - oy, wz = cz - oz;
    const float tc = wx * dx + wy * dy + wz * dz;
    const float px = wx - tc * dx, py = wy - tc * dy, pz = wz - tc * dz;
    const float chord2 = r2 - (px * px + py * py + pz * pz);
    // The chord meets [tMin, tMax]: its centre lies within sqrt(chord2) of the interval.
    const float gap = (tMin - tc > tc - tMax ? tMin - tc : tc - tMax) - slack;
    return (chord2 > 0.0f) & ((gap <= 0.0f) | (gap * gap <= chord2));
}

// Where the ray o + t d (float, as Embree holds it) enters the sphere of centre c and radius
// r (a support sphere grown by a margin) in [tnear, ...): tnear when it starts inside,
// infinity when it misses it: the test of a first-entry query (BundleGather::firstEntry), and
// of SphereSet::firstEntry.
inline float sphereEntry(float cx, float cy, float cz, float r, float ox, float oy, float oz,
                         float dx, float dy, float dz, float tnear) {
    const float wx = cx - ox, wy = cy - oy, wz = cz - oz;
    const float tc = wx * dx + wy * dy + wz * dz;
    const float px = wx - tc * dx, py = wy - tc * dy, pz = wz - tc * dz;
    const float chord2 = r * r - (px * px + py * py + pz * pz);
    const float half = std::sqrt(chord2 > 0.0f ? chord2 : 0.0f);
    const float t = tc - half - r * GATHER_SLACK;
    const bool meets = (chord2 > 0.0f) & (tc + half >= tnear);
    return meets ? (t > tnear ? t : tnear) : INFINITY;
}

// Support spheres in a fixed order (particle order where they come from a neighbourhood),
// padded to whole vectors with spheres that meet no ray: what the secondary rays of one hit
// (which share its origin) gather from, one ray at a time, without a traversal each.
class SphereSet {
  public:
    void clear() { mCount = 0; }
    // `grown`: the radius grown by the margin of the first-entry queries.
    void add(const glm::vec3& centre, float radius, float grown, std::uint32_t prim);
    // Pads to whole vectors; call before select().
    void finish();
    std::size_t size() const { return mCount; }

    // The spheres that the ray (origin, unit direction) meets over [tMin, tMax], in this
    // set's order, by the test of a gather: appended to `out` (prims) or, when `subset` is
    // given, make it (finished); with `grown`, those whose grown sphere it meets.
    void select(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax,
                std::vector<std::uint32_t>* out, SphereSet* subset, bool grown = false) const;

    // The answer of BundleGather::firstEntry (same margin) for the line origin + t direction
    // over [tnear, tfar], where the set alone decides it: the first entry into a grown sphere
    // of the set lies at most at tLimit (up to which the set must hold every grown sphere
    // the line meets), and every sphere entered there has one radius (Embree's traversal
    // order picks among them). False where it does not.
    bool firstEntry(const glm::dvec3& origin, const glm::dvec3& direction, double tnear,
                    double tfar, double tLimit, double& t, std::uint32_t& prim) const;

  private:
    // Room for n spheres and their padding (contents kept).
    void reserve(std::size_t n);

    std::size_t mCount = 0;
    std::vector<float> mX, mY, mZ, mRadius, mGrown;
    std::vector<std::uint32_t> mPrim;
    mutable std::vector<int> mMeets;
    mutable std::vector<float> mEntry;
};

class BundleGather {
  public:
    // `margin[i]`: how far (scene units) any bundle ray may pass from the central ray near
    // particle i; the Embree bounds are the support spheres grown by it. The spans need not
    // outlive the object.
    // `order`: groupOrder(centers), when the caller has it already (two gathers over the same
    // particles share it); computed when empty.
    BundleGather(const EmbreeDevice& device, std::span<const glm::vec3> centers,
                 std::span<const float> supportRadius, std::span<const float> margin,
                 std::span<const std::uint32_t> order = {});
    ~BundleGather();
    BundleGather(const BundleGather&) = delete;
    BundleGather& operator=(const BundleGather&) = delete;

    // Appends (in no particular order) every support sphere that overlaps some ray of the
    // bundle over its interval. The central ray's [tnear, tfar] must cover the part of it
    // abreast of every ray interval.
    void gather(const RayBundle& bundle, const glm::dvec3& centralOrigin,
                const glm::dvec3& centralDirection, double tnear, double tfar,
                std::vector<std::uint32_t>& out) const;

    struct Entry {
        double t;  // where the line enters the grown sphere (never after it), or tnear inside it
        std::uint32_t prim;
    };
    // The first support sphere grown by the margin along the line origin + t direction (unit)
    // in [tnear, tfar]: no ray of a bundle around the line enters a support sphere before its
    // point abreast of entry.t.
    bool firstEntry(const glm::dvec3& origin, const glm::dvec3& direction, double tnear,
                    double tfar, Entry& entry) const;
    // firstEntry for up to PACKET separate rays at once (a packet: much cheaper than a query
    // per ray when they are coherent); for a single ray, a safe start before its own entry.
    // Returns the mask of the rays that found one.
    static constexpr int PACKET = 8;
    struct Query {
        glm::dvec3 origin, direction;
        double tnear, tfar;
    };
    std::uint32_t firstEntries(int count, const Query* queries, Entry* entries) const;

    // Particles are handed to Embree in groups of up to GROUP neighbours (in Morton order):
    // one callback then tests the whole group against the central ray, in one vector, instead
    // of one callback per particle (most of which miss: Embree calls for every leaf whose box
    // the ray crosses).
    static constexpr int GROUP = 8;
    // The particles in group order: each run of GROUP (the last may be shorter) are
    // neighbours (median splits across the widest extent).
    static std::vector<std::uint32_t> groupOrder(std::span<const glm::vec3> centers);
    struct alignas(32) Group {
        // Centre and the support radius grown by the margin (and the float slack) of each
        // member; unused members have radius 0 and meet nothing.
        float x[GROUP], y[GROUP], z[GROUP], grown[GROUP];
        float radius[GROUP];  // the support radius itself
        std::uint32_t prim[GROUP];
    };

  private:
    static void bounds(const RTCBoundsFunctionArguments* args);
    static void intersect(const RTCIntersectFunctionNArguments* args);
    static void occluded(const RTCOccludedFunctionNArguments* args);
    static void firstEntryTest(const RTCIntersectFunctionNArguments* args);

    std::vector<Group> mGroups;
    RTCScene mScene = nullptr;
};

}  // namespace twinrender::raymarch
