#include "raymarch/bundle_gather.h"

#include <array>
#include <cmath>

namespace twinrender::raymarch {

namespace {

struct BundleContext {
    RTCIntersectContext context;
    const RayBundle* bundle;
    std::vector<BundleHit>* out;
    const glm::vec3* centers;
    const float* radius;
};

// Relative slack of the float sphere test: it may report a sphere that only grazes a ray
// (the exact candidate test then drops it), never miss one.
constexpr float SLACK = 1e-4f;

// Bit i as a table: a per-lane variable shift has no SSE2 instruction, a load does.
constexpr auto RAY_BIT = [] {
    std::array<std::uint32_t, RayBundle::MAX_RAYS> bits{};
    for (int i = 0; i < RayBundle::MAX_RAYS; ++i) bits[i] = 1u << i;
    return bits;
}();

}  // namespace

void RayBundle::set(int i, const glm::dvec3& o, const glm::dvec3& d, double t0, double t1) {
    ox[i] = static_cast<float>(o.x);
    oy[i] = static_cast<float>(o.y);
    oz[i] = static_cast<float>(o.z);
    dx[i] = static_cast<float>(d.x);
    dy[i] = static_cast<float>(d.y);
    dz[i] = static_cast<float>(d.z);
    tMin[i] = static_cast<float>(t0);
    tMax[i] = static_cast<float>(t1);
}

BundleGather::BundleGather(const EmbreeDevice& device, std::span<const glm::vec3> centers,
                           std::span<const float> supportRadius, std::span<const float> margin)
    : mDevice(device), mCenters(centers), mRadius(supportRadius), mMargin(margin) {
    mScene = rtcNewScene(device.get());
    rtcSetSceneBuildQuality(mScene, RTC_BUILD_QUALITY_MEDIUM);
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
    const glm::vec3 c = self->mCenters[args->primID];
    const float r = (self->mRadius[args->primID] + self->mMargin[args->primID]) * (1.0f + SLACK);
    args->bounds_o->lower_x = c.x - r;
    args->bounds_o->lower_y = c.y - r;
    args->bounds_o->lower_z = c.z - r;
    args->bounds_o->upper_x = c.x + r;
    args->bounds_o->upper_y = c.y + r;
    args->bounds_o->upper_z = c.z + r;
}

// Eight rays at a time where the CPU has AVX2 (chosen at run time), four otherwise.
__attribute__((target_clones("avx2", "default")))
void BundleGather::intersect(const RTCIntersectFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const BundleContext*>(args->context);
    const RayBundle& b = *ctx->bundle;
    const glm::vec3 c = ctx->centers[args->primID];
    const float r = ctx->radius[args->primID];
    const float r2 = r * r * (1.0f + 2.0f * SLACK);
    const float slack = r * SLACK;
    std::uint32_t mask = 0;
    // Branch-free, so that it runs a vector of rays at a time.
#pragma omp simd reduction(| : mask)
    for (int i = 0; i < b.count; ++i) {
        const float wx = c.x - b.ox[i], wy = c.y - b.oy[i], wz = c.z - b.oz[i];
        const float tc = wx * b.dx[i] + wy * b.dy[i] + wz * b.dz[i];
        const float px = wx - tc * b.dx[i], py = wy - tc * b.dy[i], pz = wz - tc * b.dz[i];
        const float chord2 = r2 - (px * px + py * py + pz * pz);
        const float half = std::sqrt(chord2 > 0.0f ? chord2 : 0.0f) + slack;
        const bool overlaps = (chord2 > 0.0f) & (tc + half >= b.tMin[i]) & (tc - half <= b.tMax[i]);
        const std::uint32_t bit = RAY_BIT[i];
        mask |= bit & (0u - static_cast<std::uint32_t>(overlaps));
    }
    if (mask) ctx->out->push_back({args->primID, mask});
    // No hit is reported: traversal goes on through every sphere along the central ray.
}

void BundleGather::occluded(const RTCOccludedFunctionNArguments*) {}

void BundleGather::gather(const RayBundle& bundle, const glm::dvec3& o, const glm::dvec3& d,
                          double tnear, double tfar, std::vector<BundleHit>& out) const {
    BundleContext ctx;
    rtcInitIntersectContext(&ctx.context);
    ctx.bundle = &bundle;
    ctx.out = &out;
    ctx.centers = mCenters.data();
    ctx.radius = mRadius.data();
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
    rtcIntersect1(mScene, &ctx.context, &rh);
}

}  // namespace twinrender::raymarch
