#include "raymarch/bundle_gather.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace twinrender::raymarch {

namespace {

// A gather (bundle and out set) or a first-entry query (bundle null).
struct BundleContext {
    RTCIntersectContext context;
    const RayBundle* bundle;
    std::vector<std::uint32_t>* out;
    const BundleGather::Sphere* spheres;
    const float* radius;
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

// Relative slack of the float sphere tests: they may report a sphere that only grazes a ray
// (the field build tests it again), never miss one.
constexpr float SLACK = 1e-4f;

// Whether the sphere (c, radius) meets the query's (single) ray within its [tnear, tfar]. It
// uses the ray as Embree holds it, so that its float rounding is Embree's.
inline bool centralRayMeets(const RTCIntersectFunctionNArguments* args, const glm::vec3& c, float radius) {
    const RTCRay& ray = reinterpret_cast<const RTCRayHit*>(args->rayhit)->ray;
    const glm::vec3 w(c.x - ray.org_x, c.y - ray.org_y, c.z - ray.org_z);
    const glm::vec3 d(ray.dir_x, ray.dir_y, ray.dir_z);
    const float tc = glm::dot(w, d);
    const glm::vec3 p = w - tc * d;
    const float chord2 = radius * radius - glm::dot(p, p);
    // The chord (tc -+ sqrt(chord2)) meets [tnear, tfar], without the square root.
    const float gap = std::max(std::max(ray.tnear - tc, tc - ray.tfar), 0.0f) - radius * SLACK;
    return chord2 > 0.0f && (gap <= 0.0f || gap * gap <= chord2);
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

BundleGather::BundleGather(const EmbreeDevice& device, std::span<const glm::vec3> centers,
                           std::span<const float> supportRadius, std::span<const float> margin)
    : mDevice(device), mCenters(centers), mRadius(supportRadius), mMargin(margin) {
    mSpheres.resize(centers.size());
    for (std::size_t i = 0; i < centers.size(); ++i)
        mSpheres[i] = {centers[i].x, centers[i].y, centers[i].z, (supportRadius[i] + margin[i]) * (1.0f + SLACK)};
    mScene = rtcNewScene(device.get());
    // The quick (Morton) build: gathers ran as fast on its tree as on the medium one's, and it
    // takes half the time to build.
    rtcSetSceneBuildQuality(mScene, RTC_BUILD_QUALITY_LOW);
    RTCGeometry geom = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(centers.size()));
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
    const Sphere& s = self->mSpheres[args->primID];
    const glm::vec3 c(s.x, s.y, s.z);
    const float r = s.grown;
    args->bounds_o->lower_x = c.x - r;
    args->bounds_o->lower_y = c.y - r;
    args->bounds_o->lower_z = c.z - r;
    args->bounds_o->upper_x = c.x + r;
    args->bounds_o->upper_y = c.y + r;
    args->bounds_o->upper_z = c.z + r;
}

// Eight rays at a time where the CPU has x86-64-v3 (AVX2, FMA; chosen at run time), four
// otherwise.
__attribute__((target_clones("arch=x86-64-v3", "default")))
void BundleGather::intersect(const RTCIntersectFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const BundleContext*>(args->context);
    if (!ctx->bundle) {
        firstEntryTest(args);
        return;
    }
    const RayBundle& b = *ctx->bundle;
    const BundleGather::Sphere s = ctx->spheres[args->primID];
    const glm::vec3 c(s.x, s.y, s.z);
    // The central ray first: Embree calls for every box it crosses, and the grown sphere
    // inside the box is missed a good part of the time; then no ray of the bundle can meet
    // the support sphere.
    if (!centralRayMeets(args, c, s.grown)) return;
    const float r = ctx->radius[args->primID];
    const float r2 = r * r * (1.0f + 2.0f * SLACK);
    const float slack = r * SLACK;
    const int n = b.count;
    if (n % RayBundle::LANES != 0) __builtin_unreachable();
    // A vector of rays at a time (branch-free within it), until one meets the sphere.
    int meets = 0;
    for (int v = 0; v < n && !meets; v += RayBundle::LANES) {
#pragma omp simd reduction(| : meets)
        for (int i = v; i < v + RayBundle::LANES; ++i) {
            const float wx = c.x - b.ox[i], wy = c.y - b.oy[i], wz = c.z - b.oz[i];
            const float tc = wx * b.dx[i] + wy * b.dy[i] + wz * b.dz[i];
            const float px = wx - tc * b.dx[i], py = wy - tc * b.dy[i], pz = wz - tc * b.dz[i];
            const float chord2 = r2 - (px * px + py * py + pz * pz);
            // The chord meets [tMin, tMax]: its centre lies within sqrt(chord2) of the interval.
            const float gap = (b.tMin[i] - tc > tc - b.tMax[i] ? b.tMin[i] - tc : tc - b.tMax[i]) - slack;
            meets |= (chord2 > 0.0f) & ((gap <= 0.0f) | (gap * gap <= chord2));
        }
    }
    if (meets) ctx->out->push_back(args->primID);
    // No hit is reported: traversal goes on through every sphere along the central ray.
}

// A first-entry query (one ray): reports the sphere as a hit where the ray enters it, so that
// Embree keeps the nearest and prunes what lies beyond.
void BundleGather::firstEntryTest(const RTCIntersectFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const BundleContext*>(args->context);
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
    const BundleGather::Sphere s = ctx->spheres[args->primID];
    const glm::vec3 c(s.x, s.y, s.z);
    const float r = s.grown;
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const glm::vec3 o(RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i),
                          RTCRayN_org_z(ray, args->N, i));
        const glm::vec3 d(RTCRayN_dir_x(ray, args->N, i), RTCRayN_dir_y(ray, args->N, i),
                          RTCRayN_dir_z(ray, args->N, i));
        const glm::vec3 w = c - o;
        const float tc = glm::dot(w, d);
        const glm::vec3 p = w - tc * d;
        const float chord2 = r * r - glm::dot(p, p);
        if (chord2 <= 0.0f) continue;
        const float half = std::sqrt(chord2);
        const float tnear = RTCRayN_tnear(ray, args->N, i);
        float& tfar = RTCRayN_tfar(ray, args->N, i);
        if (tc + half < tnear) continue;
        const float t = std::max(tc - half - r * SLACK, tnear);
        if (t > tfar) continue;
        tfar = t;
        RTCHitN_primID(hit, args->N, i) = args->primID;
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
    ctx.spheres = mSpheres.data();
    ctx.radius = mRadius.data();
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
    ctx.spheres = mSpheres.data();
    ctx.radius = mRadius.data();
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
    ctx.spheres = mSpheres.data();
    ctx.radius = mRadius.data();
    RTCRayHit rh = makeRayHit(o, d, tnear, tfar);
    rtcIntersect1(mScene, &ctx.context, &rh);
}

}  // namespace twinrender::raymarch
