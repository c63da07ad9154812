#include "raymarch/bundle_gather.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "raymarch/vector_loops.h"

namespace twinrender::raymarch {

namespace {

// A gather (bundle and out set) or a first-entry query (bundle null).
struct BundleContext {
    RTCIntersectContext context;
    const RayBundle* bundle;
    std::vector<std::uint32_t>* out;
    const BundleGather::Group* groups;
};

RTCRayHit makeRayHit(const glm::dvec3& o, const glm::dvec3& d, double tnear, double tfar) {
    RTCRayHit rh{};
    rh.ray.org_x = static_cast<float>(o.x);
    rh.ray.org_y = static_cast<float>(o.y);
    rh.ray.org_z = static_cast<float>(o.z);
    rh.ray.dir_x = static_cast<float>(d.x);
    rh.ray.dir_y = static_cast<float>(d.y);
    rh.ray.dir_z = static_cast<float>(d.z);
    rh.ray.tnear = static_cast<float>(std::max(tnear, 0.0));
    rh.ray.tfar = static_cast<float>(tfar);
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

constexpr float SLACK = GATHER_SLACK;

// Marks in `meets` the members of a group whose grown sphere meets the query's (single) ray
// within its [tnear, tfar]. It uses the ray as Embree holds it, so that its float rounding is
// Embree's.
inline void centralRayMeets(const RTCIntersectFunctionNArguments* args,
                            const BundleGather::Group& g, int meets[BundleGather::GROUP]) {
    const RTCRay& ray = reinterpret_cast<const RTCRayHit*>(args->rayhit)->ray;
    const float ox = ray.org_x, oy = ray.org_y, oz = ray.org_z;
    const float dx = ray.dir_x, dy = ray.dir_y, dz = ray.dir_z;
    const float tnear = ray.tnear, tfar = ray.tfar;
#pragma omp simd
    for (int k = 0; k < BundleGather::GROUP; ++k) {
        const float wx = g.x[k] - ox, wy = g.y[k] - oy, wz = g.z[k] - oz, radius = g.grown[k];
        const float tc = wx * dx + wy * dy + wz * dz;
        const float px = wx - tc * dx, py = wy - tc * dy, pz = wz - tc * dz;
        const float chord2 = radius * radius - (px * px + py * py + pz * pz);
        // The chord (tc -+ sqrt(chord2)) meets [tnear, tfar], without the square root.
        const float before = tnear - tc, after = tc - tfar;
        const float outside = before > after ? before : after;
        const float gap = (outside > 0.0f ? outside : 0.0f) - radius * SLACK;
        meets[k] = (chord2 > 0.0f) & ((gap <= 0.0f) | (gap * gap <= chord2));
    }
}

// Orders ids[0, n) so that each run of GROUP holds neighbours: splits at a multiple of
// GROUP across the widest extent of their centres until each part fits a group.
void orderForGroups(std::uint32_t* ids, std::size_t n, std::span<const glm::vec3> centers) {
    constexpr std::size_t G = BundleGather::GROUP;
    if (n <= G) return;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (std::size_t k = 0; k < n; ++k) {
        lo = glm::min(lo, centers[ids[k]]);
        hi = glm::max(hi, centers[ids[k]]);
    }
    const glm::vec3 extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    const std::size_t half = std::min((n / 2 + G - 1) / G * G, n - 1);
    std::nth_element(ids, ids + half, ids + n, [&](std::uint32_t a, std::uint32_t b) {
        return centers[a][axis] < centers[b][axis] ||
               (centers[a][axis] == centers[b][axis] && a < b);
    });
    orderForGroups(ids, half, centers);
    orderForGroups(ids + half, n - half, centers);
}

}  // namespace

void RayBundle::add(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1) {
    const int i = count++;
    ox[i] = static_cast<float>(o.x);
    oy[i] = static_cast<float>(o.y);
    oz[i] = static_cast<float>(o.z);
    dx[i] = static_cast<float>(d.x);
    dy[i] = static_cast<float>(d.y);
    dz[i] = static_cast<float>(d.z);
    tMin[i] = static_cast<float>(t0);
    tMax[i] = static_cast<float>(t1);
}

void RayBundle::finish() {
    while (count % LANES != 0) add(glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0), INFINITY, -INFINITY);
}

namespace {

// Bit k set where flags[k] is (k < LANES).
inline std::uint32_t laneMask(const int* flags) {
    std::uint32_t mask = 0;
    for (std::size_t k = 0; k < LANES; ++k) mask |= std::uint32_t(flags[k] != 0) << k;
    return mask;
}

}  // namespace

void SphereSet::reserve(std::size_t n) {
    const std::size_t padded = padToLanes(n);
    if (mPrim.size() >= padded) return;
    const std::size_t capacity = std::max(padded, 2 * mPrim.size());
    for (auto* v : {&mX, &mY, &mZ, &mRadius, &mGrown}) v->resize(capacity);
    mPrim.resize(capacity);
}

void SphereSet::add(const glm::vec3& centre, float radius, float grown, std::uint32_t prim) {
    reserve(mCount + 1);
    mX[mCount] = centre.x;
    mY[mCount] = centre.y;
    mZ[mCount] = centre.z;
    mRadius[mCount] = radius;
    mGrown[mCount] = grown;
    mPrim[mCount++] = prim;
}

void SphereSet::finish() {
    // Radius 0 meets nothing (chord2 <= 0).
    reserve(mCount);
    for (std::size_t i = mCount; i < padToLanes(mCount); ++i) {
        mX[i] = mY[i] = mZ[i] = mRadius[i] = mGrown[i] = 0.0f;
        mPrim[i] = 0;
    }
}

TWINRENDER_VECTOR_CLONES
void SphereSet::select(const glm::dvec3& origin, const glm::dvec3& direction, double tMin,
                       double tMax, std::vector<std::uint32_t>* out, SphereSet* subset,
                       bool grown) const {
    // The ray as RayBundle::add rounds it.
    const float ox = static_cast<float>(origin.x), oy = static_cast<float>(origin.y),
                oz = static_cast<float>(origin.z);
    const float dx = static_cast<float>(direction.x), dy = static_cast<float>(direction.y),
                dz = static_cast<float>(direction.z);
    const float t0 = static_cast<float>(tMin), t1 = static_cast<float>(tMax);
    const std::size_t n = padToLanes(mCount);
    if (n % LANES != 0) __builtin_unreachable();
    if (mMeets.size() < n) mMeets.resize(mPrim.size());
    const float *x = mX.data(), *y = mY.data(), *z = mZ.data(), *radius = mRadius.data(),
                *tested = grown ? mGrown.data() : radius;
    int* meets = mMeets.data();
#pragma omp simd
    for (std::size_t i = 0; i < n; ++i)
        meets[i] = rayMeetsSupport(x[i], y[i], z[i], tested[i], ox, oy, oz, dx, dy, dz, t0, t1);
    // Compacted a vector at a time: few of the spheres are met.
    if (!subset) {
        for (std::size_t v = 0; v < n; v += LANES)
            for (std::uint32_t mask = laneMask(meets + v); mask != 0; mask &= mask - 1)
                out->push_back(mPrim[v + std::size_t(__builtin_ctz(mask))]);
        return;
    }
    subset->reserve(mCount);
    float *sx = subset->mX.data(), *sy = subset->mY.data(), *sz = subset->mZ.data(),
          *sr = subset->mRadius.data(), *sg = subset->mGrown.data();
    std::uint32_t* sp = subset->mPrim.data();
    std::size_t m = 0;
    for (std::size_t v = 0; v < n; v += LANES)
        for (std::uint32_t mask = laneMask(meets + v); mask != 0; mask &= mask - 1) {
            const std::size_t i = v + std::size_t(__builtin_ctz(mask));
            sx[m] = x[i];
            sy[m] = y[i];
            sz[m] = z[i];
            sr[m] = radius[i];
            sg[m] = mGrown[i];
            sp[m++] = mPrim[i];
        }
    subset->mCount = m;
    subset->finish();
}

TWINRENDER_VECTOR_CLONES
bool SphereSet::firstEntry(const glm::dvec3& origin, const glm::dvec3& direction, double tnear,
                           double tfar, double tLimit, double& t, std::uint32_t& prim) const {
    // The line as makeRayHit rounds it.
    const float ox = static_cast<float>(origin.x), oy = static_cast<float>(origin.y),
                oz = static_cast<float>(origin.z);
    const float dx = static_cast<float>(direction.x), dy = static_cast<float>(direction.y),
                dz = static_cast<float>(direction.z);
    const float t0 = static_cast<float>(std::max(tnear, 0.0)), t1 = static_cast<float>(tfar);
    const std::size_t n = padToLanes(mCount);
    if (n % LANES != 0) __builtin_unreachable();
    mEntry.resize(mPrim.size());
    const float *x = mX.data(), *y = mY.data(), *z = mZ.data(), *grown = mGrown.data();
    float* entry = mEntry.data();
    float best = INFINITY;
#pragma omp simd reduction(min : best)
    for (std::size_t i = 0; i < n; ++i) {
        const float e = sphereEntry(x[i], y[i], z[i], grown[i], ox, oy, oz, dx, dy, dz, t0);
        entry[i] = e;
        best = minf(best, e <= t1 ? e : INFINITY);
    }
    if (!(best <= t1) || !(double(best) <= tLimit)) return false;
    // The first sphere entered there; another of a different radius there leaves it open.
    std::size_t first = n;
    for (std::size_t i = 0; i < mCount; ++i) {
        if (entry[i] != best) continue;
        if (first == n)
            first = i;
        else if (mRadius[i] != mRadius[first])
            return false;
    }
    t = entry[first];
    prim = mPrim[first];
    return true;
}

std::vector<std::uint32_t> BundleGather::groupOrder(std::span<const glm::vec3> centers) {
    std::vector<std::uint32_t> ids(centers.size());
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<std::uint32_t>(i);
    orderForGroups(ids.data(), ids.size(), centers);
    return ids;
}

BundleGather::BundleGather(const EmbreeDevice& device, std::span<const glm::vec3> centers,
                           std::span<const float> supportRadius, std::span<const float> margin,
                           std::span<const std::uint32_t> order) {
    std::vector<std::uint32_t> own;
    if (order.empty()) {
        own = groupOrder(centers);
        order = own;
    }
    mGroups.resize((order.size() + GROUP - 1) / GROUP);
    for (std::size_t k = 0; k < order.size(); ++k) {
        Group& g = mGroups[k / GROUP];
        const std::size_t m = k % GROUP;
        const std::uint32_t i = order[k];
        g.x[m] = centers[i].x;
        g.y[m] = centers[i].y;
        g.z[m] = centers[i].z;
        g.grown[m] = (supportRadius[i] + margin[i]) * (1.0f + SLACK);
        g.radius[m] = supportRadius[i];
        g.prim[m] = i;
    }
    mScene = rtcNewScene(device.get());
    // The quick (Morton) build: gathers ran as fast on its tree as on the medium one's, and it
    // takes half the time to build.
    rtcSetSceneBuildQuality(mScene, RTC_BUILD_QUALITY_LOW);
    RTCGeometry geom = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(mGroups.size()));
    rtcSetGeometryUserData(geom, this);
    rtcSetGeometryBoundsFunction(geom, &BundleGather::bounds, this);
    rtcSetGeometryIntersectFunction(geom, &BundleGather::intersect);
    rtcSetGeometryOccludedFunction(geom, &BundleGather::occluded);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(mScene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(mScene);
    device.check("building the bundle-gather BVH");
}

BundleGather::~BundleGather() {
    if (mScene) rtcReleaseScene(mScene);
}

void BundleGather::bounds(const RTCBoundsFunctionArguments* args) {
    const auto* self = static_cast<const BundleGather*>(args->geometryUserPtr);
    const Group& g = self->mGroups[args->primID];
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (int k = 0; k < GROUP; ++k) {
        if (!(g.grown[k] > 0.0f)) continue;
        const glm::vec3 c(g.x[k], g.y[k], g.z[k]);
        lo = glm::min(lo, c - g.grown[k]);
        hi = glm::max(hi, c + g.grown[k]);
    }
    args->bounds_o->lower_x = lo.x;
    args->bounds_o->lower_y = lo.y;
    args->bounds_o->lower_z = lo.z;
    args->bounds_o->upper_x = hi.x;
    args->bounds_o->upper_y = hi.y;
    args->bounds_o->upper_z = hi.z;
}

// Eight rays at a time where the CPU has x86-64-v3 (AVX2, FMA; chosen at run time), four
// otherwise.
TWINRENDER_VECTOR_CLONES
void BundleGather::intersect(const RTCIntersectFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const BundleContext*>(args->context);
    if (!ctx->bundle) {
        firstEntryTest(args);
        return;
    }
    const RayBundle& b = *ctx->bundle;
    const Group& g = ctx->groups[args->primID];
    // The central ray first: Embree calls for every leaf box it crosses, and a member's grown
    // sphere is missed a good part of the time; then no ray of the bundle can meet its
    // support sphere.
    int central[GROUP];
    centralRayMeets(args, g, central);
    const int n = b.count;
    if (n % RayBundle::LANES != 0) __builtin_unreachable();
    for (int m = 0; m < GROUP; ++m) {
        if (!central[m]) continue;
        const float cx = g.x[m], cy = g.y[m], cz = g.z[m], r = g.radius[m];
        // A vector of rays at a time (branch-free within it), until one meets the sphere.
        int meets = 0;
        for (int v = 0; v < n && !meets; v += RayBundle::LANES) {
#pragma omp simd reduction(| : meets)
            for (int i = v; i < v + RayBundle::LANES; ++i)
                meets |= rayMeetsSupport(cx, cy, cz, r, b.ox[i], b.oy[i], b.oz[i], b.dx[i], b.dy[i],
                                         b.dz[i], b.tMin[i], b.tMax[i]);
        }
        if (meets) ctx->out->push_back(g.prim[m]);
    }
    // No hit is reported: traversal goes on through every group along the central ray.
}

// A first-entry query (one ray): reports the sphere as a hit where the ray enters it, so that
// Embree keeps the nearest and prunes what lies beyond.
TWINRENDER_VECTOR_CLONES
void BundleGather::firstEntryTest(const RTCIntersectFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const BundleContext*>(args->context);
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
    const Group& g = ctx->groups[args->primID];
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const float ox = RTCRayN_org_x(ray, args->N, i), oy = RTCRayN_org_y(ray, args->N, i),
                    oz = RTCRayN_org_z(ray, args->N, i);
        const float dx = RTCRayN_dir_x(ray, args->N, i), dy = RTCRayN_dir_y(ray, args->N, i),
                    dz = RTCRayN_dir_z(ray, args->N, i);
        const float tnear = RTCRayN_tnear(ray, args->N, i);
        float& tfar = RTCRayN_tfar(ray, args->N, i);
        // Each member's entry (infinite where the ray misses it), then the first of them.
        float entry[GROUP];
#pragma omp simd
        for (int k = 0; k < GROUP; ++k)
            entry[k] =
                sphereEntry(g.x[k], g.y[k], g.z[k], g.grown[k], ox, oy, oz, dx, dy, dz, tnear);
        int first = -1;
        for (int k = 0; k < GROUP; ++k)
            if (entry[k] <= tfar && (first < 0 || entry[k] < entry[first])) first = k;
        if (first < 0) continue;
        tfar = entry[first];
        RTCHitN_primID(hit, args->N, i) = g.prim[first];
        RTCHitN_geomID(hit, args->N, i) = args->geomID;
    }
}

void BundleGather::occluded(const RTCOccludedFunctionNArguments*) {}

bool BundleGather::firstEntry(const glm::dvec3& o, const glm::dvec3& d, double tnear, double tfar,
                              Entry& entry) const {
    BundleContext ctx;
    rtcInitIntersectContext(&ctx.context);
    ctx.bundle = nullptr;
    ctx.out = nullptr;
    ctx.groups = mGroups.data();
    RTCRayHit rh = makeRayHit(o, d, tnear, tfar);
    rtcIntersect1(mScene, &ctx.context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    entry = {rh.ray.tfar, rh.hit.primID};
    return true;
}

std::uint32_t BundleGather::firstEntries(int count, const Query* queries, Entry* entries) const {
    BundleContext ctx;
    rtcInitIntersectContext(&ctx.context);
    ctx.context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    ctx.bundle = nullptr;
    ctx.out = nullptr;
    ctx.groups = mGroups.data();
    alignas(32) int valid[PACKET];
    RTCRayHit8 rh;
    for (int i = 0; i < PACKET; ++i) {
        const Query& q = queries[std::min(i, count - 1)];
        valid[i] = i < count ? -1 : 0;
        rh.ray.org_x[i] = static_cast<float>(q.origin.x);
        rh.ray.org_y[i] = static_cast<float>(q.origin.y);
        rh.ray.org_z[i] = static_cast<float>(q.origin.z);
        rh.ray.dir_x[i] = static_cast<float>(q.direction.x);
        rh.ray.dir_y[i] = static_cast<float>(q.direction.y);
        rh.ray.dir_z[i] = static_cast<float>(q.direction.z);
        rh.ray.tnear[i] = static_cast<float>(std::max(q.tnear, 0.0));
        rh.ray.tfar[i] = static_cast<float>(q.tfar);
        rh.ray.time[i] = 0.0f;
        rh.ray.mask[i] = 0xffffffffu;
        rh.ray.id[i] = 0;
        rh.ray.flags[i] = 0;
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.primID[i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect8(valid, mScene, &ctx.context, &rh);
    std::uint32_t mask = 0;
    for (int i = 0; i < count; ++i) {
        if (rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
        entries[i] = {rh.ray.tfar[i], rh.hit.primID[i]};
        mask |= 1u << i;
    }
    return mask;
}

void BundleGather::gather(const RayBundle& bundle, const glm::dvec3& o, const glm::dvec3& d,
                          double tnear, double tfar, std::vector<std::uint32_t>& out) const {
    BundleContext ctx;
    rtcInitIntersectContext(&ctx.context);
    ctx.bundle = &bundle;
    ctx.out = &out;
    ctx.groups = mGroups.data();
    RTCRayHit rh = makeRayHit(o, d, tnear, tfar);
    rtcIntersect1(mScene, &ctx.context, &rh);
}

}  // namespace twinrender::raymarch
