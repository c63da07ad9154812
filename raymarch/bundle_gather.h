// Gathering support spheres for a bundle of nearly parallel rays with one Embree traversal.
//
// Gathering per ray costs one Embree callback per sphere crossed (~70 per ray near a
// surface). Neighbouring pixels cross almost the same spheres, so a bundle of up to 32 rays
// (a pixel block, or the shadow rays of one) is gathered at once: an Embree user geometry
// holds every particle with its support sphere (radius 2h) inflated by a margin, the bundle's
// central ray is traced through it, and the callback tests the real support sphere against
// every ray of the bundle over that ray's own interval. Each reported sphere comes with the
// mask of the rays it overlaps. The result is exact as long as every ray of the bundle stays
// within the margin of the central ray near the spheres it crosses; the caller guarantees it.
#pragma once

#include <cstdint>
#include <embree3/rtcore.h>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "raymarch/embree_device.h"

namespace twinrender::raymarch {

struct RayBundle {
    static constexpr int MAX_RAYS = 32;
    int count = 0;
    // Per ray, in float: the test only selects spheres; candidates are rebuilt in double.
    float ox[MAX_RAYS], oy[MAX_RAYS], oz[MAX_RAYS];
    float dx[MAX_RAYS], dy[MAX_RAYS], dz[MAX_RAYS];
    float tMin[MAX_RAYS], tMax[MAX_RAYS];  // the interval of each ray to gather over

    void set(int i, const glm::dvec3& origin, const glm::dvec3& direction, double t0, double t1);
};

struct BundleHit {
    std::uint32_t prim;
    std::uint32_t mask;  // bit i: the sphere overlaps ray i over its interval
};

class BundleGather {
public:
    // `margin[i]`: how far (scene units) any bundle ray may pass from the central ray near
    // particle i; the Embree bounds are the support spheres grown by it.
    BundleGather(const EmbreeDevice& device, std::span<const glm::vec3> centers,
                 std::span<const float> supportRadius, std::span<const float> margin);
    ~BundleGather();
    BundleGather(const BundleGather&) = delete;
    BundleGather& operator=(const BundleGather&) = delete;

    // Appends every support sphere that overlaps some ray of the bundle over its interval.
    // The central ray's [tnear, tfar] must cover the part of it next to every ray interval.
    void gather(const RayBundle& bundle, const glm::dvec3& centralOrigin,
                const glm::dvec3& centralDirection, double tnear, double tfar,
                std::vector<BundleHit>& out) const;

private:
    static void bounds(const RTCBoundsFunctionArguments* args);
    static void intersect(const RTCIntersectFunctionNArguments* args);
    static void occluded(const RTCOccludedFunctionNArguments* args);

    const EmbreeDevice& mDevice;
    std::span<const glm::vec3> mCenters;
    std::span<const float> mRadius;
    std::span<const float> mMargin;
    RTCScene mScene = nullptr;
};

}  // namespace twinrender::raymarch
