// Finding the implicit surface along rays, a pixel block at a time (docs/design.md,
// "The reference raymarcher": Embree finds the candidate particles along each ray segment,
// then phi and dphi/dt are evaluated along the ray).
//
// A block's rays advance together in rounds: each round, every unfinished ray takes its next
// segment (a few h long), one bundle gather (bundle_gather.h) finds the support spheres that
// overlap some ray's segment, and each ray's first crossing in its segment is searched
// (first_crossing.h) among them. They are taken in particle order, which is also the
// summation order, so the result does not depend on Embree's traversal order or on threads.
// Empty space is skipped with one query for the block, and a ray's search starts just before
// where the tangent plane of a neighbouring pixel's crossing meets it, when the field is
// proven below the level up to there.
// Shadow rays of a block are parallel (a directional light) and march the same way, in
// bundles that stay within the shadow margin of their central line. The secondary rays of one
// hit (occlusion, emitters: from one point in many directions) march alone, each its own
// bundle, but gather once for the hit: every support sphere that the cone of their
// directions meets within their reach, from which each ray's segments select theirs by the
// gather's own test (a ray that meets none of them is done without a march).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/camera.h"
#include "core/particles.h"
#include "raymarch/embree_device.h"
#include "raymarch/settings.h"

namespace twinrender::raymarch {

// Where a ray meets the surface, with everything the AOV image records.
struct SurfaceHit {
    double t = 0.0;            // ray parameter of the crossing
    glm::dvec3 position{0.0};  // at t
    glm::dvec3 outside{0.0};   // a point on the ray just outside the surface (phi < level)
    glm::vec3 normal{0.0f};    // unit, outward: -grad(phi) normalised
    glm::vec2 uv{0.0f};
    std::uint32_t body = 0;
    std::uint32_t material = 0;
    glm::vec3 glow{0.0f};  // kernel-weighted blackbody glow
    double hRef = 0.0;     // smallest h of the particles around the hit, for tolerances
};

struct TraceCounters {
    std::uint64_t unresolved = 0;   // rays given up at the iteration limit (reported)
    std::uint64_t candidates = 0;   // support spheres overlapping a searched segment
    std::uint64_t evaluations = 0;  // passes over a segment's candidates (samples, bounds)
    std::uint64_t segments = 0;     // ray segments searched
    std::uint64_t bundles = 0;      // bundle gathers
};

class SurfaceTracer {
  public:
    static constexpr int BLOCK = 8;               // pixel block side (of 4, 6, 8, 16: the fastest)
    static constexpr int MAX_RAYS = 64;           // rays per bundle
    static constexpr double SHADOW_MARGIN = 0.3;  // shadow-bundle spread allowed, in units of h

    // `occlusionRays`: traceOpen will be called (it needs the shadow rays' gather even when
    // settings.shadows is off).
    SurfaceTracer(const EmbreeDevice& device, const core::Camera& camera,
                  const core::SceneParticles& particles, const Settings& settings,
                  bool occlusionRays = false);
    ~SurfaceTracer();

    // Per-thread working memory (opaque; its deleter lives with its definition).
    class Workspace;
    struct WorkspaceDeleter {
        void operator()(Workspace* w) const;
    };
    using WorkspacePtr = std::unique_ptr<Workspace, WorkspaceDeleter>;
    WorkspacePtr makeWorkspace() const;

    // Whether a camera ray of the pixel block whose centre `central` passes through may meet
    // the surface (false: none can; always true with plain spheres).
    bool blockMayHit(const core::Ray& central) const;
    // Camera rays of one pixel block (n <= MAX_RAYS, samples anywhere inside the block's
    // pixels, in rows of `rowLength` rays); `central` is the ray through the block's centre.
    void tracePrimary(int n, int rowLength, const core::Ray* rays, const double* tnear,
                      const double* tfar, const core::Ray& central, SurfaceHit* hits, bool* found,
                      Workspace& w) const;
    // 1 where the light reaches the hit, 0 where the surface occludes it, for the hits of the
    // last tracePrimary call on this workspace.
    void traceShadows(int n, const SurfaceHit* hits, const bool* found, const glm::dvec3& toLight,
                      float* visibility, Workspace& w) const;

    // The fraction of the `count` directions (unit, in the hemisphere about hit.normal) along
    // which the surface is not met within `radius` of the hit: the ambient occlusion's open
    // fraction when they are cosine-weighted (raymarch/ao_hemisphere.h). `openEach`, when
    // given, receives each direction's answer. Needs occlusionRays.
    float traceOpen(const SurfaceHit& hit, const glm::dvec3* directions, int count, double radius,
                    Workspace& w, bool* openEach = nullptr) const;

    // Where the ray from just outside `from` (a hit) along `direction` (unit) first meets the
    // surface, with its attributes: false where it leaves the scene first. A ray alone, as an
    // occlusion ray; for the light of emitting surfaces. Needs occlusionRays.
    bool traceFirst(const SurfaceHit& from, const glm::dvec3& direction, SurfaceHit& hit,
                    Workspace& w) const;
    // traceFirst for `count` directions from one hit (found[j], hits[j]), the same answers:
    // their parts within `reach` of the hit (e.g. the far side of an emitter's bounding
    // sphere) select their spheres from one gather of those that the cone about `axis` (unit)
    // of half-angle acos(cosHalf) meets there, rather than each segment from a gather of its
    // own. The cone should hold every direction (else theirs is taken); the same cone, reach
    // and hit in the next call (the next round of one hit's directions) reuse the gather.
    void traceFirst(const SurfaceHit& from, const glm::dvec3* directions, int count,
                    const glm::dvec3& axis, double cosHalf, double reach, SurfaceHit* hits,
                    bool* found, Workspace& w) const;

    const TraceCounters& counters(const Workspace& w) const;
    void resetCounters(Workspace& w) const;
    double buildMs() const { return mBuildMs; }

  private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
    double mBuildMs = 0.0;
};

}  // namespace twinrender::raymarch
