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
