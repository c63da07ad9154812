#include "raymarch/surface_tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/particle_grid.h"
#include "core/sph_kernel.h"
#include "raymarch/bundle_gather.h"
#include "raymarch/first_crossing.h"
#include "raymarch/hit_attributes.h"
#include "raymarch/particle_batch.h"
#include "raymarch/ray_field.h"
#include "raymarch/sphere_scene.h"
#include "raymarch/vector_loops.h"

namespace twinrender::raymarch {

// The tracer's own types and helpers. A named namespace, not an anonymous one: the Workspace
// and Impl below hold these types, and in a unity build (where this file is included) a class
// with members of anonymous-namespace types draws -Wsubobject-linkage.
namespace surface_tracer_detail {

// One ray's state while its bundle marches.
struct MarchRay {
    core::Ray ray;
    double t = 0.0;                // where the next segment starts
    double tEnd = 0.0;             // where the ray stops
    double hRef = 0.0;             // scale of the particles near t (segment length, tolerances)
    double segmentScale = 1.0;     // the next segment's length, in units of the setting
    int emptySegments = 0;         // segments in a row that met no support (EMPTY_RUN)
    bool needEntry = true;         // skip empty space to the next support sphere first
    bool sharedEntry = true;       // that skip may come from one query for the bundle (once)
    bool fromSharedEntry = false;  // the next segment starts at a shared entry
    bool active = true;
    bool hit = false;
};

// Whether the ray meets the box within [t0, t1] (slab test).
bool rayMeetsBox(const core::Ray& ray, double t0, double t1, const glm::dvec3& lo,
                 const glm::dvec3& hi) {
    for (int k = 0; k < 3; ++k) {
        const double inv = 1.0 / ray.direction[k];
        double a = (lo[k] - ray.origin[k]) * inv, b = (hi[k] - ray.origin[k]) * inv;
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
    }
    return t0 <= t1;
}

struct BodyRange {
    glm::dvec3 lo, hi;  // support bounds
    glm::dvec3 center;  // a sphere around every support: the box's centre ...
    double radius;      // ... and the largest distance of a support's edge from it
    double hMin;
};

// Whether the ray meets the sphere within [t0, t1].
bool rayMeetsSphere(const core::Ray& ray, double t0, double t1, const glm::dvec3& center,
                    double radius) {
    const glm::dvec3 w = center - ray.origin;
    const double t = std::clamp(glm::dot(w, ray.direction), t0, t1);
    const glm::dvec3 off = w - t * ray.direction;
    return glm::dot(off, off) <= radius * radius;
}

// Whether the ray meets the body's supports' bounds within [t0, t1].
bool rayMeetsBody(const core::Ray& ray, double t0, double t1, const BodyRange& b) {
    return rayMeetsSphere(ray, t0, t1, b.center, b.radius) && rayMeetsBox(ray, t0, t1, b.lo, b.hi);
}

// Sorts distinct values (particle indices below 2^31) in increasing order. A gather returns a
// few dozen; each one's rank (how many are smaller) is counted in vectors, without the
// branches of a comparison sort, whose outcomes are unpredictable here.
TWINRENDER_VECTOR_CLONES
void sortDistinct(std::vector<std::uint32_t>& values, std::vector<std::uint32_t>& scratch) {
    constexpr std::size_t RANK_SORT_LIMIT = 128;
    const std::size_t n = values.size();
    if (n > RANK_SORT_LIMIT) {
        std::sort(values.begin(), values.end());
        return;
    }
    scratch.resize(n);
    const std::int32_t* v = reinterpret_cast<const std::int32_t*>(values.data());
    for (std::size_t i = 0; i < n; ++i) {
        const std::int32_t x = v[i];
        std::uint32_t rank = 0;
#pragma omp simd reduction(+ : rank)
        for (std::size_t j = 0; j < n; ++j) rank += v[j] < x;
        scratch[rank] = static_cast<std::uint32_t>(x);
    }
    values.swap(scratch);
}

double maxAbsCoordinate(const glm::dvec3& p) {
    return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
}

// An entry found in float may land a little after the true one: the segment starts this many
// h before it.
constexpr double ENTRY_BACKOFF = 1e-3;
// A segment that starts at a shared entry begins up to the bundle's spread before the ray's
// own entry; it is this many h longer, so that most rays still find their crossing in it.
constexpr double SHARED_ENTRY_EXTRA = 0.5;
// Shadow rays mostly prove that nothing ahead reaches the level (one or two evaluations per
// segment, against four or five to refine a crossing), so their segments are longer: one
// gather takes most of them out of the support spheres.
constexpr double SHADOW_SEGMENT_SCALE = 4.0;
// Rays that graze the thin outer layer (silhouettes) miss segment after segment at the first
// evaluation: after each such miss the next segment is twice as long, up to this factor.
constexpr double MAX_SEGMENT_SCALE = 4.0;
// A primary ray's search is hinted to start this many h before the crossing of the block's
// last ray that found one (neighbouring pixels' crossings lie close).
constexpr double HINT_BACKOFF = 0.1;
// ... and this many h (along the normal) before the tangent plane of a neighbour's crossing,
// when the ray meets that plane at an angle of at most acos(MIN_PLANE_HINT_COSINE) from the normal.
constexpr double PLANE_HINT_BACKOFF = 0.01;
constexpr double MIN_PLANE_HINT_COSINE = 0.2;
// A segment is at least this fraction of the size of the coordinates along the ray (|t| plus
// the origin's largest coordinate): one of 2 h, for an h far below the rounding of the
// coordinates (a file's h = 1e-30 beside h = 0.5), would not move t, and the ray would enter
// the same support forever. Float positions resolve 2^-24 of their size: every particle that
// has a support of its own at its place has 2 h far above this.
constexpr double MIN_SEGMENT_FRACTION = 0x1p-40;
// After this many segments in a row that met no support (a ray inside the grown sphere of a
// particle, whose margin of a pixel block's spread is far larger than its h), each next
// segment is twice as long: crossing a margin of any size takes tens of segments, not
// margin / h. In the scenes' camera rays such runs end after a few segments.
constexpr int EMPTY_RUN = 64;
// A hit's neighbourhood (gatherNear) holds the particles within its reach plus this many
// support radii (the gathers' float tests pass spheres up to 2e-4 of their radius beyond it)
// ...
constexpr double NEAR_SLACK = 1.001;
// ... plus this fraction of the coordinates' size (float rounding of the rays' origins and
// directions, 2^-24 of it).
constexpr double NEAR_ROUNDING = 1e-5;
// ... and about the rays' cone, this much in the cosine of the angle from its axis (rounding
// of the directions).
constexpr double COSINE_SLACK = 1e-6;
// A cone given for a set of directions is widened by this much in the cosine (their rounding);
// a hemisphere's directions may point this little behind its plane.
constexpr double CONE_SLACK = 1e-9;
constexpr double HEMISPHERE_SLACK = 1e-9;
// A neighbourhood of more spheres than this is not gathered: selecting from it for each ray
// would cost more than the rays' own gathers.
constexpr std::size_t NEAR_LIMIT = 2048;
// A cone narrower than this half-angle (radians) is bounded by a ball about its axis' middle,
// a wider one by the ball of its reach about its apex.
constexpr double NARROW_CONE = 0.25 * M_PI;

// The directions of rays from one origin: within half-angle acos(cosHalf) of the axis (unit).
struct RayCone {
    glm::dvec3 axis{0.0, 0.0, 1.0};
    double cosHalf = -1.0;
};

// A cone about the given unit directions: about their mean (every direction when they
// cancel out).
RayCone coneOf(const glm::dvec3* directions, int count) {
    glm::dvec3 sum(0.0);
    for (int j = 0; j < count; ++j) sum += directions[j];
    const double length = glm::length(sum);
    RayCone cone;
    if (!(length > 1e-3 * count)) return cone;
    cone.axis = sum / length;
    cone.cosHalf = 1.0;
    for (int j = 0; j < count; ++j)
        cone.cosHalf =
            std::min(cone.cosHalf, glm::dot(directions[j], cone.axis) / glm::length(directions[j]));
    return cone;
}

}  // namespace surface_tracer_detail

using namespace surface_tracer_detail;

class SurfaceTracer::Workspace {
  public:
    RayField field;                     // the segment being searched
    std::vector<std::uint32_t> prims;   // this round's gather, in particle order
    std::vector<std::uint32_t> sorted;  // sortDistinct's scratch
    ParticleBatch batch;                // their data
    std::vector<float> weights;         // kernel weights at a hit
    std::vector<int> groupEnds;         // shadow bundles
    // The secondary rays of one hit share its origin: the support spheres that any of them
    // may meet within `nearReach` of `nearOrigin` (gatherNear), and those of the ray being
    // marched (its segments' gathers select from them).
    SphereSet near, raySpheres;
    std::vector<std::uint32_t> nearIds;
    glm::dvec3 nearOrigin{NAN};
    double nearReach = NAN;
    RayCone nearCone;
    bool nearUsable = false;
    bool nearGrown = false;     // w.near holds every grown sphere too (its entries are decided)
    double lastCrossing = NAN;  // the block's last primary crossing
    int rowLength = 0;          // primary rays come in rows of this many
    MarchRay rays[MAX_RAYS];
    TraceCounters counters;
};

struct SurfaceTracer::Impl {
    const core::Camera& camera;
    const core::SceneParticles& particles;
    Settings settings;
    std::vector<FieldParticle> fieldParticles;
    std::vector<HitAttributes> hitAttributes;  // per particle
    std::unique_ptr<SphereScene> spheres;      // plain spheres (spheres mode)
    // Support spheres grown by the spread of a pixel block's rays (camera rays), and by the
    // shadow margin (shadow rays; only with shadows on).
    std::unique_ptr<BundleGather> bundles, shadowBundles;
    std::vector<BodyRange> bodyRanges;
    double sinBlock = 0.0;
    // Secondary rays (occlusionRays): the particles by place, and their support radii as the
    // gathers hold them.
    std::unique_ptr<core::ParticleGrid> grid;
    std::vector<float> supportRadii, grownRadii;  // grown: as the shadow gather's entry queries
    double largestGrown = 0.0;

    Impl(const EmbreeDevice& device, const core::Camera& cam, const core::SceneParticles& p,
         const Settings& st, bool occlusionRays)
        : camera(cam), particles(p), settings(st) {
        const auto& ps = p.particles;
        const std::size_t n = ps.size();
        // A ray of a pixel block is at most sinBlock away from the block's central ray per unit
        // of distance from the camera (pixel angles are largest at the image centre).
        const double pixelAngle = 2.0 * cam.tanHalfFovY() / cam.height();
        sinBlock = std::min(1.0, 1.02 * (BLOCK / std::sqrt(2.0)) * pixelAngle);
        if (st.spheres) {
            std::vector<float> radii(n);
            for (std::size_t i = 0; i < n; ++i)
                radii[i] = static_cast<float>(st.sphereRadius) * ps.h[i];
            spheres = std::make_unique<SphereScene>(device, ps.position, radii);
            return;
        }
        std::vector<float> supportRadius(n), margin(n), shadowMargin(n);
        for (std::size_t i = 0; i < n; ++i) {
            supportRadius[i] = static_cast<float>(core::M4_SUPPORT) * ps.h[i];
            // Near particle i a camera ray of the block passes within
            // (|x_i - camera| + 2h) sinBlock of the central ray; a shadow ray of a bundle
            // within SHADOW_MARGIN h (groupParallel). Two trees: shadow bundles spread more
            // than most pixel blocks, and growing every sphere by the larger margin would
            // cost the camera rays' gathers more callbacks.
            const double primary =
                (glm::length(glm::dvec3(ps.position[i]) - cam.position()) + supportRadius[i]) *
                sinBlock;
            margin[i] = static_cast<float>(primary);
            shadowMargin[i] = static_cast<float>(SHADOW_MARGIN * ps.h[i]);
        }
        fieldParticles = makeFieldParticles(ps);
        hitAttributes.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            hitAttributes[i] = {ps.uv[i].x, ps.uv[i].y, ps.glow[i].r, ps.glow[i].g, ps.glow[i].b};
        const std::vector<std::uint32_t> order = BundleGather::groupOrder(ps.position);
        bundles = std::make_unique<BundleGather>(device, ps.position, supportRadius, margin, order);
        if (st.shadows || occlusionRays)
            shadowBundles = std::make_unique<BundleGather>(device, ps.position, supportRadius,
                                                           shadowMargin, order);
        if (occlusionRays && n > 0) {
            grid = std::make_unique<core::ParticleGrid>(ps);
            supportRadii = supportRadius;
            grownRadii.resize(n);
            for (std::size_t i = 0; i < n; ++i)
                grownRadii[i] = (supportRadius[i] + shadowMargin[i]) * (1.0f + GATHER_SLACK);
            largestGrown = *std::max_element(grownRadii.begin(), grownRadii.end());
        }
        auto addRange = [&](std::size_t begin, std::size_t end) {
            BodyRange r{glm::dvec3(INFINITY), glm::dvec3(-INFINITY), glm::dvec3(0.0), 0.0,
                        INFINITY};
            for (std::size_t i = begin; i < end; ++i) {
                const double s = supportRadius[i];
                r.lo = glm::min(r.lo, glm::dvec3(ps.position[i]) - s);
                r.hi = glm::max(r.hi, glm::dvec3(ps.position[i]) + s);
                r.hMin = std::min(r.hMin, double(ps.h[i]));
            }
            r.center = 0.5 * (r.lo + r.hi);
            for (std::size_t i = begin; i < end; ++i)
                r.radius = std::max(r.radius, glm::length(glm::dvec3(ps.position[i]) - r.center) +
                                                  supportRadius[i]);
            // Rounding of the float positions and of the tests.
            r.radius *= 1.0 + 1e-6;
            bodyRanges.push_back(r);
        };
        for (const auto& b : p.bodies) addRange(b.begin, b.end);
        if (p.bodies.empty()) addRange(0, n);
    }

    CrossingSettings crossingSettings(double hRef) const {
        CrossingSettings cs;
        cs.level = settings.surfaceLevel;
        cs.tolerance = settings.rootTolerance * hRef;
        cs.maxStep = settings.stepWindow * hRef;
        cs.maxIterations = settings.maxIterations;
        return cs;
    }

    // Splits the parallel rays ids[0, count) into groups that stay within the shadow margin of
    // their group's central line (through its mean origin) near any particle they may meet, so
    // that each is gathered as one bundle: a group that does not fit is halved across its
    // widest spread. Appends each group's end (in the reordered ids) to `ends`.
    void groupParallel(int* ids, int count, const glm::dvec3& direction, const Workspace& w,
                       std::vector<int>& ends, int offset = 0) const {
        glm::dvec3 mean(0.0);
        for (int k = 0; k < count; ++k) mean += w.rays[ids[k]].ray.origin;
        mean /= double(count);
        // The smallest h of the bodies the rays cross.
        double hMin = INFINITY;
        for (const auto& b : bodyRanges) {
            bool meets = false;
            for (int k = 0; k < count && !meets && b.hMin < hMin; ++k) {
                const MarchRay& r = w.rays[ids[k]];
                meets = rayMeetsBody(r.ray, r.t, r.tEnd, b);
            }
            if (meets) hMin = std::min(hMin, b.hMin);
        }
        glm::dvec3 perp[MAX_RAYS] = {};
        int widest = 0;
        double widest2 = 0.0;
        for (int k = 0; k < count; ++k) {
            const glm::dvec3 off = w.rays[ids[k]].ray.origin - mean;
            perp[k] = off - glm::dot(off, direction) * direction;
            if (glm::dot(perp[k], perp[k]) > widest2) {
                widest2 = glm::dot(perp[k], perp[k]);
                widest = k;
            }
        }
        const double limit = SHADOW_MARGIN * hMin * 0.999;
        if (widest2 <= limit * limit) {
            ends.push_back(offset + count);
            return;
        }
        // Order along the widest offset and split at the median.
        const glm::dvec3 axis = perp[widest];
        int order[MAX_RAYS], sorted[MAX_RAYS];
        for (int k = 0; k < count; ++k) order[k] = k;
        std::sort(order, order + count, [&](int a, int b) {
            const double pa = glm::dot(perp[a], axis), pb = glm::dot(perp[b], axis);
            return pa < pb || (pa == pb && ids[a] < ids[b]);
        });
        for (int k = 0; k < count; ++k) sorted[k] = ids[order[k]];
        std::copy(sorted, sorted + count, ids);
        const int half = count / 2;
        groupParallel(ids, half, direction, w, ends, offset);
        groupParallel(ids + half, count - half, direction, w, ends, offset + half);
    }

    // Skips empty space: moves each active ray of the bundle that needs it to its next
    // support-sphere entry (that of the sphere grown by the margin, a little before), or ends
    // it when there is none. Rays asking for the first time skip the bodies their lines miss,
    // then share one query along the central line: a bundle that meets nothing (most blocks,
    // most shadow bundles) costs that one query. A primary ray then starts abreast of the
    // shared entry; a shared entry can lie well before a ray's own, so later entries (and
    // shadow rays, whose bundles spread more) take their own queries, packets of rays.
    void enter(const int* ids, int n, const glm::dvec3& origin, const glm::dvec3& centralDirection,
               bool parallel, Workspace& w) const {
        const auto& ps = particles.particles;
        int shared[MAX_RAYS], own[MAX_RAYS], sharedCount = 0, ownCount = 0;
        for (int k = 0; k < n; ++k) {
            MarchRay& r = w.rays[ids[k]];
            if (!r.active || !r.needEntry) continue;
            // Rays whose rest misses every body's bounds end here.
            bool meets = false;
            for (const auto& b : bodyRanges) meets = meets || rayMeetsBody(r.ray, r.t, r.tEnd, b);
            if (!meets) {
                r.active = false;
                continue;
            }
            if (r.sharedEntry) {
                r.sharedEntry = false;
                shared[sharedCount++] = ids[k];
            } else {
                own[ownCount++] = ids[k];
            }
        }
        if (sharedCount > 0) {
            // Ray i's parameter s lies abreast of origin + a direction with a = along_i + s cos_i.
            double along[MAX_RAYS], cosine[MAX_RAYS], a0 = INFINITY, a1 = -INFINITY;
            bool positive = true;
            for (int k = 0; k < sharedCount; ++k) {
                const MarchRay& r = w.rays[shared[k]];
                along[k] = glm::dot(r.ray.origin - origin, centralDirection);
                cosine[k] = glm::dot(r.ray.direction, centralDirection);
                positive = positive && cosine[k] > 0.0;
                a0 = std::min(a0, along[k] + r.t * cosine[k]);
                a1 = std::max(a1, along[k] + r.tEnd * cosine[k]);
            }
            BundleGather::Entry e{};
            const double shift = std::min(a0, 0.0);
            const BundleGather& tree = gatherFor(parallel);
            const bool found =
                !positive || tree.firstEntry(origin + shift * centralDirection, centralDirection,
                                             a0 - shift, a1 - shift, e);
            e.t += shift;
            for (int k = 0; k < sharedCount; ++k) {
                MarchRay& r = w.rays[shared[k]];
                if (!found) {
                    r.active = false;
                    continue;
                }
                if (positive) {
                    // No support sphere is entered before the point abreast of the grown
                    // one's entry.
                    r.t =
                        std::max(r.t, (e.t - along[k]) / cosine[k] - ENTRY_BACKOFF * ps.h[e.prim]);
                    if (!parallel) {
                        r.hRef = ps.h[e.prim];
                        r.needEntry = false;
                        r.fromSharedEntry = true;
                        r.segmentScale = firstSegmentScale(r, e.prim);
                        continue;
                    }
                }
                own[ownCount++] = shared[k];
            }
        }
        BundleGather::Query queries[MAX_RAYS];
        for (int k = 0; k < ownCount; ++k) {
            const MarchRay& r = w.rays[own[k]];
            queries[k] = {r.ray.origin, r.ray.direction, r.t, r.tEnd};
        }
        for (int k = 0; k < ownCount; k += BundleGather::PACKET) {
            const int m = std::min(BundleGather::PACKET, ownCount - k);
            BundleGather::Entry entries[BundleGather::PACKET];
            const std::uint32_t found = gatherFor(parallel).firstEntries(m, queries + k, entries);
            for (int j = 0; j < m; ++j) {
                MarchRay& r = w.rays[own[k + j]];
                if (!(found >> j & 1u)) {
                    r.active = false;
                    continue;
                }
                r.hRef = ps.h[entries[j].prim];
                r.t = std::max(r.t, entries[j].t - ENTRY_BACKOFF * r.hRef);
                r.needEntry = false;
            }
        }
    }

    // What enter() does for a ray marched alone (a bundle of one, parallel) whose grown
    // spheres up to localEnd are `set`'s, where the set decides its entry queries
    // (SphereSet::firstEntry): the same answers without a traversal. Leaves the ray to enter()
    // where it does not.
    void enterFromSet(MarchRay& r, const SphereSet& set, double localEnd) const {
        if (!r.active || !r.needEntry) return;
        const auto& ps = particles.particles;
        bool meets = false;
        for (const auto& b : bodyRanges) meets = meets || rayMeetsBody(r.ray, r.t, r.tEnd, b);
        if (!meets) return;
        double t = 0.0;
        std::uint32_t prim = 0;
        if (r.sharedEntry) {
            // The bundle's line is the ray's own (along 0, no shift).
            const double cosine = glm::dot(r.ray.direction, r.ray.direction);
            if (!(cosine > 0.0) || !(r.t * cosine > 0.0) ||
                !set.firstEntry(r.ray.origin, r.ray.direction, r.t * cosine, r.tEnd * cosine,
                                localEnd, t, prim))
                return;
            r.sharedEntry = false;
            r.t = std::max(r.t, t / cosine - ENTRY_BACKOFF * ps.h[prim]);
        }
        if (!set.firstEntry(r.ray.origin, r.ray.direction, r.t, r.tEnd, localEnd, t, prim)) return;
        r.hRef = ps.h[prim];
        r.t = std::max(r.t, t - ENTRY_BACKOFF * r.hRef);
        r.needEntry = false;
    }

    // The gather of camera-ray bundles, or of shadow bundles (parallel rays).
    const BundleGather& gatherFor(bool parallel) const {
        return parallel ? *shadowBundles : *bundles;
    }

    // A camera ray's first segment is the segment length deep measured along the normal of
    // the entered body's bounding sphere, not along the ray: one entering at a slant (toward
    // a limb) has a longer way to the surface, and a segment that falls short costs its block
    // another round of gathers. (1/cos of the incidence, up to the largest scale: ball.ssf
    // takes 6.2k gathers instead of 7.4k, 294k segments instead of 360k.)
    double firstSegmentScale(const MarchRay& r, std::uint32_t entered) const {
        const auto& ps = particles.particles;
        const BodyRange& body = bodyRanges[bodyRanges.size() > 1 ? ps.body[entered] : 0];
        const glm::dvec3 out = r.ray.origin + r.t * r.ray.direction - body.center;
        const double length = glm::length(out);
        const double facing = length > 0.0 ? -glm::dot(r.ray.direction, out) / length : 1.0;
        return std::clamp(1.0 / std::max(facing, 1e-3), 1.0, MAX_SEGMENT_SCALE);
    }

    // Marches the rays w.rays[ids[0, n)] to their first crossing as one bundle; fills
    // hits[id] for the rays that find one when `hits` is given. Primary bundles pass the
    // block's central direction, shadow bundles (parallel rays within the shadow margin of
    // the central line through their mean origin, groupParallel) the direction of the light.
    // `local` (a single ray, n = 1): a set holding every support sphere the ray may meet up to
    // its parameter `localEnd`; the segments that end there gather from it.
    void march(const int* ids, int n, const glm::dvec3& centralDirection, bool parallel,
               Workspace& w, SurfaceHit* hits, const SphereSet* local = nullptr,
               double localEnd = -INFINITY) const {
        const double segmentLength =
            settings.segmentLength * (parallel ? SHADOW_SEGMENT_SCALE : 1.0);
        // The central line: through the mean origin (the camera, for primary rays).
        glm::dvec3 origin(0.0);
        for (int k = 0; k < n; ++k) origin += w.rays[ids[k]].ray.origin;
        origin /= double(n);
        for (;;) {
            if (local && w.rays[ids[0]].active && w.rays[ids[0]].needEntry &&
                w.rays[ids[0]].tEnd <= localEnd) {
                // No support sphere ahead: nothing left to meet.
                const MarchRay& r = w.rays[ids[0]];
                w.prims.clear();
                local->select(r.ray.origin, r.ray.direction, r.t, r.tEnd, &w.prims, nullptr);
                if (w.prims.empty()) return;
            }
            if (local && w.nearGrown) enterFromSet(w.rays[ids[0]], *local, localEnd);
            enter(ids, n, origin, centralDirection, parallel, w);
            // The bundle: every active ray's next segment.
            RayBundle bundle;
            int lane[MAX_RAYS];
            double segEnd[MAX_RAYS];
            for (int k = 0; k < n; ++k) {
                MarchRay& r = w.rays[ids[k]];
                if (!r.active) continue;
                const double extra = r.fromSharedEntry ? SHARED_ENTRY_EXTRA : 0.0;
                r.fromSharedEntry = false;
                const double least =
                    MIN_SEGMENT_FRACTION * (std::abs(r.t) + maxAbsCoordinate(r.ray.origin));
                const int doublings = std::clamp(r.emptySegments - EMPTY_RUN, 0, 2048);
                const double length = std::ldexp(
                    std::max((segmentLength * r.segmentScale + extra) * r.hRef, least), doublings);
                segEnd[bundle.count] = std::min(r.t + length, r.tEnd);
                lane[bundle.count] = ids[k];
                bundle.add(r.ray.origin, r.ray.direction, r.t, segEnd[bundle.count]);
            }
            const int active = bundle.count;
            if (active == 0) return;
            // The part of the central line abreast of every segment.
            double tnear = INFINITY, tfar = -INFINITY;
            for (int j = 0; j < active; ++j) {
                const MarchRay& r = w.rays[lane[j]];
                for (double t : {r.t, segEnd[j]}) {
                    const double along =
                        glm::dot(r.ray.origin + t * r.ray.direction - origin, centralDirection);
                    tnear = std::min(tnear, along);
                    tfar = std::max(tfar, along);
                }
            }
            // Shift the central origin so that its range starts at 0.
            const double shift = std::min(tnear, 0.0);
            const double slack = 1e-6 * std::max(std::abs(tfar - shift), 1.0);
            w.prims.clear();
            if (local && segEnd[0] <= localEnd) {
                // The gather's own test over the ray's set, which is in particle order.
                const MarchRay& r = w.rays[lane[0]];
                local->select(r.ray.origin, r.ray.direction, r.t, segEnd[0], &w.prims, nullptr);
            } else {
                bundle.finish();
                gatherFor(parallel).gather(bundle, origin + shift * centralDirection,
                                           centralDirection, tnear - shift - slack,
                                           tfar - shift + slack, w.prims);
                ++w.counters.bundles;
                // Particle order: it is the summation order, so that it does not depend on
                // Embree's traversal order.
                sortDistinct(w.prims, w.sorted);
            }
            w.batch.assign(w.prims, fieldParticles, hits ? hitAttributes.data() : nullptr);

            for (int j = 0; j < active; ++j) {
                MarchRay& r = w.rays[lane[j]];
                ++w.counters.segments;
                double hNear = 0.0;
                ++r.emptySegments;
                if (!w.prims.empty()) {
                    w.field.build(r.ray.origin, r.ray.direction, r.t, segEnd[j], w.batch);
                    w.counters.candidates += w.field.candidates();
                    if (w.field.candidates() > 0) r.emptySegments = 0;
                    // phi never exceeds the sum of the peaks (a ray grazing the outer layer),
                    // and it is 0 before the first support interval begins: a primary search
                    // without a hint starts there (with one, the bound up to the hint covers
                    // the way; shadow rays start inside the supports).
                    const double hint = hits ? primaryHint(lane[j], w, hits) : NAN;
                    double start = r.t;
                    if (w.field.peakSum() < settings.surfaceLevel)
                        start = INFINITY;
                    else if (hits && !(hint > r.t && hint < segEnd[j]))
                        start = std::max(r.t, w.field.supportStart());
                    const Crossing crossing =
                        start < segEnd[j] ? findFirstCrossing(w.field, start, segEnd[j],
                                                              crossingSettings(r.hRef), hint)
                                          : Crossing{};
                    w.counters.evaluations += crossing.evaluations;
                    switch (crossing.status) {
                        case Crossing::Status::Hit:
                        case Crossing::Status::Inside:
                            r.hit = true;
                            r.active = false;
                            if (hits) {
                                surfaceHit(r, crossing, w, hits[lane[j]]);
                                w.lastCrossing = crossing.t;
                            }
                            continue;
                        case Crossing::Status::Unresolved:
                            ++w.counters.unresolved;
                            r.active = false;
                            continue;
                        case Crossing::Status::Miss:
                            break;
                    }
                    if (crossing.evaluations <= 1)
                        r.segmentScale = std::min(2.0 * r.segmentScale, MAX_SEGMENT_SCALE);
                    // The next segment's scale: the particles that reach past this one.
                    hNear = w.field.largestHBeyond(segEnd[j]);
                }
                r.t = segEnd[j];
                if (r.t >= r.tEnd) {
                    r.active = false;
                    continue;
                }
                // None: empty space follows, skip it.
                if (hNear > 0.0)
                    r.hRef = hNear;
                else
                    r.needEntry = true;
            }
        }
    }

    // Where a primary ray's search may start: a little before where the tangent plane of a
    // neighbour's crossing (the ray before it in its row, else the one above it) meets the
    // ray; else a little before the block's last crossing.
    double primaryHint(int id, const Workspace& w, const SurfaceHit* hits) const {
        const MarchRay& r = w.rays[id];
        for (const int neighbour : {id % w.rowLength != 0 ? id - 1 : -1, id - w.rowLength}) {
            if (neighbour < 0 || !w.rays[neighbour].hit) continue;
            const SurfaceHit& h = hits[neighbour];
            const glm::dvec3 normal(h.normal);
            const double facing = -glm::dot(r.ray.direction, normal);
            if (facing < MIN_PLANE_HINT_COSINE) continue;
            const double t = glm::dot(h.position - r.ray.origin, normal) / -facing;
            return t - PLANE_HINT_BACKOFF * r.hRef / facing;
        }
        return w.lastCrossing - HINT_BACKOFF * r.hRef;
    }

    // Everything the AOV image records about a ray's crossing, from the segment's candidates.
    void surfaceHit(const MarchRay& r, const Crossing& crossing, Workspace& w,
                    SurfaceHit& hit) const {
        hit.t = crossing.t;
        hit.position = r.ray.origin + crossing.t * r.ray.direction;
        hit.outside = r.ray.origin + crossing.tBelow * r.ray.direction;
        surfaceAttributes(crossing.t, w, hit);
        if (!(hit.hRef > 0.0)) hit.hRef = r.hRef;
    }

    // Analytic normal and kernel-weighted attributes at the surface point p(t) of the segment
    // in w.field.
    void surfaceAttributes(double t, Workspace& w, SurfaceHit& hit) const {
        const auto& ps = particles.particles;
        const RayField& field = w.field;
        const SurfacePoint point = surfacePoint(field, t, w.weights);
        const double length = glm::length(point.gradient);
        hit.normal = length > 0.0 ? glm::vec3(-point.gradient / length) : glm::vec3(0.0f);
        hit.hRef = point.hMin;
        // The particles whose support contains the point are those of positive weight.
        const std::size_t lanes = field.size();
        float* weights = w.weights.data();
        const std::uint32_t* index = field.indices();
        // The visible body: the one with the largest summed weight (a few bodies at most); the
        // others' particles are left out from here on.
        std::uint32_t best = 0;
        if (particles.bodies.size() > 1) {
            std::uint32_t ids[8] = {};
            float sums[8] = {};
            int bodies = 0;
            for (std::size_t c = 0; c < lanes; ++c) {
                if (!(weights[c] > 0.0f)) continue;
                const std::uint32_t b = ps.body[index[c]];
                int m = 0;
                while (m < bodies && ids[m] != b) ++m;
                if (m == bodies && bodies < 8) {
                    ids[bodies] = b;
                    sums[bodies++] = 0.0f;
                }
                if (m < bodies) sums[m] += weights[c];
            }
            int bestM = 0;
            for (int m = 1; m < bodies; ++m)
                if (sums[m] > sums[bestM]) bestM = m;
            best = ids[bestM];
            for (std::size_t c = 0; c < lanes; ++c)
                if (ps.body[index[c]] != best) weights[c] = 0.0f;
        }
        // uv and glow: normalised kernel weights over the visible body's particles.
        HitAttributes average;
        if (!averageAttributes(w.batch, weights, lanes, average)) return;
        hit.uv = glm::vec2(average.u, average.v);
        hit.glow = glm::vec3(average.r, average.g, average.b);
        hit.body = best;
        hit.material = particles.bodies.empty() ? 0 : particles.bodies[best].material;
    }

    bool traceSphere(const core::Ray& ray, double tnear, double tfar, SurfaceHit& hit) const {
        const auto& ps = particles.particles;
        SphereScene::Hit h;
        if (!spheres->closestHit(glm::vec3(ray.origin), glm::vec3(ray.direction),
                                 static_cast<float>(tnear), static_cast<float>(tfar), h))
            return false;
        const std::uint32_t i = h.prim;
        hit.t = h.t;
        hit.position = ray.origin + double(h.t) * ray.direction;
        const glm::dvec3 off = hit.position - glm::dvec3(ps.position[i]);
        hit.normal = glm::vec3(glm::normalize(off));
        hit.hRef = ps.h[i];
        // Off the sphere along its normal, so the shadow ray does not hit its own sphere.
        hit.outside = hit.position + 1e-3 * hit.hRef * glm::dvec3(hit.normal);
        // uv extrapolated from the particle with its gradient, as an impostor does.
        glm::dvec2 uv = glm::dvec2(ps.uv[i]) + glm::dvec2(glm::dot(glm::dvec3(ps.dudx[i]), off),
                                                          glm::dot(glm::dvec3(ps.dvdx[i]), off));
        uv.x -= std::floor(uv.x);
        uv.y = std::clamp(uv.y, 0.0, 1.0);
        hit.uv = glm::vec2(uv);
        hit.body = ps.body[i];
        hit.material = ps.material[i];
        hit.glow = ps.glow[i];
        return true;
    }

    // Whether the surface is not met within `radius` of the hit along d (unit): from just
    // outside the surface, as a shadow ray, but stopping at the radius; a ray alone is its own
    // bundle (the directions spread over the hemisphere).
    // With `near`, the spheres of w.near (gatherNear(hit.outside, radius, ...)) are the ray's.
    bool openAlong(const SurfaceHit& hit, const glm::dvec3& d, double radius, Workspace& w,
                   bool near) const {
        if (settings.spheres)
            return !spheres->occluded(glm::vec3(hit.outside), glm::vec3(d), 0.0f,
                                      static_cast<float>(radius));
        MarchRay& r = w.rays[0];
        r = MarchRay{};
        r.ray = core::Ray{hit.outside, d};
        r.t = 2.0 * settings.rootTolerance * hit.hRef;
        r.tEnd = std::min(radius, exitDistance(hit.outside, d));
        if (!(r.t < r.tEnd)) return true;
        r.hRef = hit.hRef;
        r.needEntry = false;
        const int id = 0;
        if (!near) {
            march(&id, 1, d, true, w, nullptr);
            return !r.hit;
        }
        // The spheres this ray meets: none, and it is open without a march.
        w.near.select(r.ray.origin, d, r.t, r.tEnd, nullptr, &w.raySpheres, false);
        if (w.raySpheres.size() == 0) return true;
        march(&id, 1, d, true, w, nullptr, &w.raySpheres, r.tEnd);
        return !r.hit;
    }

    // Fills w.near with every support sphere (with `grownSet`, every one grown by the shadow
    // gather's margin, so that the set decides the rays' entry queries) that a ray from
    // `origin` within `cone` may meet within `reach` of it (a gather's test passes spheres a
    // little beyond their radius, and rounds the ray to float), in particle order; false (and
    // w.near unusable) where they are more than NEAR_LIMIT, or without a grid or a finite
    // reach. Kept while the origin, reach, cone and kind stay.
    bool gatherNear(const glm::dvec3& origin, double reach, const RayCone& cone, bool grownSet,
                    Workspace& w) const {
        if (origin == w.nearOrigin && reach == w.nearReach && cone.axis == w.nearCone.axis &&
            cone.cosHalf == w.nearCone.cosHalf && grownSet == w.nearGrown)
            return w.nearUsable;
        w.nearGrown = grownSet;
        w.nearOrigin = origin;
        w.nearReach = reach;
        w.nearCone = cone;
        w.nearUsable = false;
        if (!grid || !(reach > 0.0) || !std::isfinite(reach) || !std::isfinite(cone.cosHalf) ||
            !std::isfinite(maxAbsCoordinate(origin)))
            return false;
        const std::vector<float>& radii = grownSet ? grownRadii : supportRadii;
        const auto& ps = particles.particles;
        const double rounding = NEAR_ROUNDING * (maxAbsCoordinate(origin) + reach);
        const double half = std::acos(std::clamp(cone.cosHalf, -1.0, 1.0));
        const double sinHalf = std::sin(half);
        // A ball around the cone's part within reach: about the origin, or for a narrow cone
        // about the middle of its axis.
        glm::dvec3 centre = origin;
        double ball = reach;
        if (half < NARROW_CONE) {
            centre = origin + 0.5 * reach * cone.axis;
            ball = reach * std::sqrt(0.25 + std::pow(std::tan(half), 2));
        }
        w.nearIds.clear();
        bool over = false;
        grid->visitBall(
            centre, ball + NEAR_SLACK * largestGrown + rounding,
            [&](const core::ParticleGrid::Level& g, std::uint32_t begin, std::uint32_t end) {
                for (std::uint32_t k = begin; k < end && !over; ++k) {
                    const std::uint32_t i = g.index[k];
                    const double grown = NEAR_SLACK * radii[i] + rounding;
                    const glm::dvec3 off = glm::dvec3(ps.position[i]) - origin;
                    const double distance = glm::length(off);
                    if (distance - grown > reach) continue;
                    if (distance > grown && !(sinHalf <= grown / distance && cone.cosHalf < 0.0)) {
                        // Outside the cone grown by the angle b the sphere subtends (the angle
                        // from the axis above half + b, which is below pi).
                        const double sinB = grown / distance, cosB = std::sqrt(1.0 - sinB * sinB);
                        const double cosLimit = cone.cosHalf * cosB - sinHalf * sinB;
                        if (glm::dot(off, cone.axis) / distance < cosLimit - COSINE_SLACK) continue;
                    }
                    w.nearIds.push_back(i);
                    over = w.nearIds.size() > NEAR_LIMIT;
                }
            });
        if (over) return false;
        std::sort(w.nearIds.begin(), w.nearIds.end());
        w.near.clear();
        for (const std::uint32_t i : w.nearIds)
            w.near.add(ps.position[i], supportRadii[i], grownRadii[i], i);
        w.near.finish();
        w.nearUsable = true;
        return true;
    }

    // Where the ray from just outside `from` along `direction` first meets the surface
    // (SurfaceTracer::traceFirst); with `nearEnd` > 0 its part up to that parameter selects
    // its spheres from w.near.
    bool first(const SurfaceHit& from, const glm::dvec3& direction, SurfaceHit& hit, Workspace& w,
               double nearEnd) const {
        const double tEnd = exitDistance(from.outside, direction);
        if (settings.spheres)
            return traceSphere(core::Ray{from.outside, direction}, 0.0, tEnd, hit);
        // As an occlusion ray, but keeping the crossing's attributes: a row of one ray, no hint
        // from a neighbour or an earlier crossing.
        MarchRay& r = w.rays[0];
        r = MarchRay{};
        r.ray = core::Ray{from.outside, direction};
        r.t = 2.0 * settings.rootTolerance * from.hRef;
        r.tEnd = tEnd;
        if (!(r.t < r.tEnd)) return false;
        r.hRef = from.hRef;
        r.needEntry = false;
        w.rowLength = 1;
        w.lastCrossing = NAN;
        const int id = 0;
        const double localEnd = std::min(nearEnd, r.tEnd);
        if (r.t < localEnd) {
            w.near.select(r.ray.origin, direction, r.t, localEnd, nullptr, &w.raySpheres, true);
            // Nothing to meet on the whole way.
            if (w.raySpheres.size() == 0 && localEnd == r.tEnd) return false;
            march(&id, 1, direction, true, w, &hit, &w.raySpheres, localEnd);
        } else {
            march(&id, 1, direction, true, w, &hit);
        }
        return r.hit;
    }

    // Distance from p along dir to the exit of the scene bounds (no surface lies beyond).
    double exitDistance(const glm::dvec3& p, const glm::dvec3& dir) const {
        const glm::dvec3 lo = particles.boundsMin, hi = particles.boundsMax;
        double tExit = 0.0;
        for (int k = 0; k < 3; ++k)
            if (dir[k] != 0.0)
                tExit = std::max(tExit, ((dir[k] > 0.0 ? hi[k] : lo[k]) - p[k]) / dir[k]);
        return tExit + 1e-6 * glm::length(hi - lo);
    }
};

SurfaceTracer::SurfaceTracer(const EmbreeDevice& device, const core::Camera& camera,
                             const core::SceneParticles& particles, const Settings& settings,
                             bool occlusionRays) {
    const auto start = std::chrono::steady_clock::now();
    mImpl = std::make_unique<Impl>(device, camera, particles, settings, occlusionRays);
    mBuildMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

SurfaceTracer::~SurfaceTracer() = default;

SurfaceTracer::WorkspacePtr SurfaceTracer::makeWorkspace() const {
    return WorkspacePtr(new Workspace());
}

void SurfaceTracer::WorkspaceDeleter::operator()(Workspace* w) const {
    delete w;
}

const TraceCounters& SurfaceTracer::counters(const Workspace& w) const {
    return w.counters;
}
void SurfaceTracer::resetCounters(Workspace& w) const {
    w.counters = {};
}

bool SurfaceTracer::blockMayHit(const core::Ray& central) const {
    const Impl& im = *mImpl;
    if (im.settings.spheres) return true;
    for (const auto& b : im.bodyRanges) {
        // A point of a block ray at distance D from the camera lies within D sinBlock of the
        // central ray, at a parameter of it below D: the central ray meets the body's box
        // (and sphere) grown by that spread before the box's farthest distance.
        const double far =
            glm::length(0.5 * (b.lo + b.hi) - central.origin) + 0.5 * glm::length(b.hi - b.lo);
        const double grow = 1.01 * far * im.sinBlock;
        if (rayMeetsSphere(central, 0.0, far, b.center, b.radius + grow) &&
            rayMeetsBox(central, 0.0, far, b.lo - grow, b.hi + grow))
            return true;
    }
    return false;
}

void SurfaceTracer::tracePrimary(int n, int rowLength, const core::Ray* rays, const double* tnear,
                                 const double* tfar, const core::Ray& central, SurfaceHit* hits,
                                 bool* found, Workspace& w) const {
    const Impl& im = *mImpl;
    if (im.settings.spheres) {
        for (int i = 0; i < n; ++i) found[i] = im.traceSphere(rays[i], tnear[i], tfar[i], hits[i]);
        return;
    }
    w.lastCrossing = NAN;
    w.rowLength = rowLength;
    for (int i = 0; i < n; ++i) {
        MarchRay& r = w.rays[i];
        r = MarchRay{};
        r.ray = rays[i];
        r.t = tnear[i];
        r.tEnd = tfar[i];
    }
    int ids[MAX_RAYS] = {};
    for (int i = 0; i < n; ++i) ids[i] = i;
    im.march(ids, n, central.direction, false, w, hits);
    for (int i = 0; i < n; ++i) found[i] = w.rays[i].hit;
}

void SurfaceTracer::traceShadows(int n, const SurfaceHit* hits, const bool* found,
                                 const glm::dvec3& toLight, float* visibility, Workspace& w) const {
    const Impl& im = *mImpl;
    int traced[MAX_RAYS], count = 0;
    for (int i = 0; i < n; ++i) {
        MarchRay& r = w.rays[i];
        r = MarchRay{};
        r.active = false;
        visibility[i] = 0.0f;
        if (!found[i]) continue;
        const SurfaceHit& hit = hits[i];
        // n = -grad(phi)/|grad(phi)|: with n.l <= 0 the ray toward the light enters the
        // surface at once (dphi/dt >= 0), so the point is occluded; no ray is needed.
        if (glm::dot(glm::dvec3(hit.normal), toLight) <= 0.0) continue;
        if (im.settings.spheres) {
            visibility[i] =
                im.spheres->occluded(glm::vec3(hit.outside), glm::vec3(toLight), 0.0f,
                                     static_cast<float>(im.exitDistance(hit.outside, toLight)))
                    ? 0.0f
                    : 1.0f;
            continue;
        }
        // From just outside the surface; the first gather also reports the support spheres
        // that contain the origin.
        r.ray = core::Ray{hit.outside, toLight};
        r.t = 2.0 * im.settings.rootTolerance * hit.hRef;
        r.tEnd = im.exitDistance(hit.outside, toLight);
        r.hRef = hit.hRef;
        r.needEntry = false;
        r.active = true;
        traced[count++] = i;
    }
    if (count == 0) return;
    w.groupEnds.clear();
    im.groupParallel(traced, count, toLight, w, w.groupEnds);
    for (std::size_t g = 0, begin = 0; g < w.groupEnds.size(); begin = w.groupEnds[g++])
        im.march(traced + begin, w.groupEnds[g] - int(begin), toLight, true, w, nullptr);
    for (int k = 0; k < count; ++k) visibility[traced[k]] = w.rays[traced[k]].hit ? 0.0f : 1.0f;
}

float SurfaceTracer::traceOpen(const SurfaceHit& hit, const glm::dvec3* directions, int count,
                               double radius, Workspace& w, bool* openEach) const {
    const Impl& im = *mImpl;
    // The hemisphere about the normal when it holds every direction (then every round of a
    // hit's directions shares one gather), else their own cone.
    RayCone cone{glm::dvec3(hit.normal), -HEMISPHERE_SLACK};
    for (int j = 0; j < count; ++j)
        if (glm::dot(directions[j], cone.axis) < cone.cosHalf) cone = coneOf(directions, count);
    const bool near =
        !im.settings.spheres && count > 0 && im.gatherNear(hit.outside, radius, cone, false, w);
    int open = 0;
    for (int j = 0; j < count; ++j) {
        const bool isOpen = im.openAlong(hit, directions[j], radius, w, near);
        open += isOpen ? 1 : 0;
        if (openEach) openEach[j] = isOpen;
    }
    return count > 0 ? static_cast<float>(open) / static_cast<float>(count) : 1.0f;
}

bool SurfaceTracer::traceFirst(const SurfaceHit& from, const glm::dvec3& direction, SurfaceHit& hit,
                               Workspace& w) const {
    return mImpl->first(from, direction, hit, w, -INFINITY);
}

void SurfaceTracer::traceFirst(const SurfaceHit& from, const glm::dvec3* directions, int count,
                               const glm::dvec3& axis, double cosHalf, double reach,
                               SurfaceHit* hits, bool* found, Workspace& w) const {
    const Impl& im = *mImpl;
    RayCone cone{axis, cosHalf - CONE_SLACK};
    for (int j = 0; j < count; ++j)
        if (glm::dot(directions[j], cone.axis) < cone.cosHalf) cone = coneOf(directions, count);
    const bool near =
        !im.settings.spheres && count > 0 && im.gatherNear(from.outside, reach, cone, true, w);
    for (int j = 0; j < count; ++j)
        found[j] = im.first(from, directions[j], hits[j], w, near ? reach : -INFINITY);
}

}  // namespace twinrender::raymarch
