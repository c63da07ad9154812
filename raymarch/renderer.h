// The reference raymarcher (DESIGN.md, "Reference raymarcher"): the exact level set of the
// particles' colour field, found along each ray from the candidates Embree gathers, with
// analytic normals, kernel-weighted uv, emission and body, and shadow rays against the same
// implicit surface. Tiles run in parallel on the caller's oneTBB arena; every pixel is
// computed on its own, so the image is bit-identical for any thread count.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "core/camera.h"
#include "core/frame.h"
#include "core/particles.h"
#include "core/scene.h"
#include "core/texture.h"
#include "raymarch/embree_device.h"
#include "raymarch/settings.h"

namespace twinrender::raymarch {

// Where a ray meets the surface, with everything the AOV image records.
struct SurfaceHit {
    double t = 0.0;            // ray parameter of the crossing
    glm::dvec3 position{0.0};  // at t
    glm::dvec3 outside{0.0};   // a point on the ray just outside the surface (phi < level)
    glm::vec3 normal{0.0f};    // unit, outward
    glm::vec2 uv{0.0f};
    std::uint32_t body = 0;
    std::uint32_t material = 0;
    glm::vec3 glow{0.0f};      // kernel-weighted blackbody glow
    double hRef = 0.0;         // smoothing length near the hit, for tolerances
};

class Renderer {
public:
    // Builds the acceleration structure (the "build" stage). The references must outlive the
    // renderer.
    Renderer(const EmbreeDevice& device, const core::Scene& scene,
             const core::SceneParticles& particles, const std::vector<core::Material>& materials,
             const Settings& settings);
    ~Renderer();

    // Renders the AOV image. `progress` (may be empty) is called with the finished fraction,
    // from worker threads, at most once per tile.
    core::Frame render(const std::function<void(double)>& progress = {}) const;

    // The first surface crossing of a ray in [tnear, tfar]; false on a miss.
    bool traceSurface(const core::Ray& ray, double tnear, double tfar, SurfaceHit& hit) const;
    // 1 when the directional light reaches the hit, 0 when the surface occludes it.
    float lightVisibility(const SurfaceHit& hit) const;

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

}  // namespace twinrender::raymarch
