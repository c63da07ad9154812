// An Embree scene of spheres, one per particle: the particles' support spheres (radius 2h)
// for gathering candidates along a ray, or plain spheres for the cost-floor renderer.
// Embree traces in float; every result is refined in double by the caller.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "raymarch/embree_device.h"

namespace twinrender::raymarch {

class SphereScene {
  public:
    SphereScene(const EmbreeDevice& device, std::span<const glm::vec3> centers,
                std::span<const float> radii);
    ~SphereScene();
    SphereScene(const SphereScene&) = delete;
    SphereScene& operator=(const SphereScene&) = delete;

    struct Hit {
        float t;
        std::uint32_t prim;
    };
    // The nearest sphere surface crossed in [tnear, tfar] (an entry, or the exit of a sphere
    // containing the point at tnear). Returns false when there is none.
    bool closestHit(const glm::vec3& origin, const glm::vec3& direction, float tnear, float tfar,
                    Hit& hit) const;
    // True when any sphere surface is crossed in [tnear, tfar].
    bool occluded(const glm::vec3& origin, const glm::vec3& direction, float tnear,
                  float tfar) const;
    // Appends to `out` every sphere whose entry or exit lies in [tnear, tfar], in no particular
    // order and possibly twice (entry and exit). A sphere that contains the whole range is not
    // reported: the caller moves the origin back to avoid that case.
    void gather(const glm::vec3& origin, const glm::vec3& direction, float tnear, float tfar,
                std::vector<std::uint32_t>& out) const;

  private:
    static void gatherFilter(const RTCFilterFunctionNArguments* args);

    const EmbreeDevice& mDevice;
    RTCScene mScene = nullptr;
};

}  // namespace twinrender::raymarch
