#include "raymarch/sphere_scene.h"

#include <limits>

namespace twinrender::raymarch {

namespace {

// The intersect context of a gather: Embree passes it to the filter function, which records
// the hit and rejects it so that traversal goes on to every sphere along the ray.
struct GatherContext {
    RTCIntersectContext context;
    std::vector<std::uint32_t>* out;  // null: a plain closest-hit query, hits are kept
};

RTCRayHit makeRayHit(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar) {
    RTCRayHit rh{};
    rh.ray.org_x = o.x;
    rh.ray.org_y = o.y;
    rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x;
    rh.ray.dir_y = d.y;
    rh.ray.dir_z = d.z;
    rh.ray.tnear = tnear;
    rh.ray.tfar = tfar;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

}  // namespace

SphereScene::SphereScene(const EmbreeDevice& device, std::span<const glm::vec3> centers,
                         std::span<const float> radii)
    : mDevice(device) {
    mScene = rtcNewScene(device.get());
    rtcSetSceneBuildQuality(mScene, RTC_BUILD_QUALITY_MEDIUM);
    RTCGeometry geom = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), centers.size()));
    device.check("allocating the particle spheres");
    for (std::size_t i = 0; i < centers.size(); ++i) {
        v[4 * i + 0] = centers[i].x;
        v[4 * i + 1] = centers[i].y;
        v[4 * i + 2] = centers[i].z;
        v[4 * i + 3] = radii[i];
    }
    rtcSetGeometryIntersectFilterFunction(geom, &SphereScene::gatherFilter);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(mScene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(mScene);
    device.check("building the particle BVH");
}

SphereScene::~SphereScene() {
    if (mScene) rtcReleaseScene(mScene);
}

bool SphereScene::closestHit(const glm::vec3& origin, const glm::vec3& direction, float tnear,
                             float tfar, Hit& hit) const {
    GatherContext ctx;
    rtcInitIntersectContext(&ctx.context);
    ctx.out = nullptr;
    RTCRayHit rh = makeRayHit(origin, direction, tnear, tfar);
    rtcIntersect1(mScene, &ctx.context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit.t = rh.ray.tfar;
    hit.prim = rh.hit.primID;
    return true;
}

bool SphereScene::occluded(const glm::vec3& origin, const glm::vec3& direction, float tnear,
                           float tfar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh = makeRayHit(origin, direction, tnear, tfar);
    rtcOccluded1(mScene, &context, &rh.ray);
    return rh.ray.tfar == -std::numeric_limits<float>::infinity();
}

void SphereScene::gatherFilter(const RTCFilterFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const GatherContext*>(args->context);
    if (!ctx->out) return;
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        ctx->out->push_back(RTCHitN_primID(args->hit, args->N, i));
        args->valid[i] = 0;
    }
}

void SphereScene::gather(const glm::vec3& origin, const glm::vec3& direction, float tnear,
                         float tfar, std::vector<std::uint32_t>& out) const {
    GatherContext ctx;
    rtcInitIntersectContext(&ctx.context);
    ctx.out = &out;
    RTCRayHit rh = makeRayHit(origin, direction, tnear, tfar);
    rtcIntersect1(mScene, &ctx.context, &rh);
}

}  // namespace twinrender::raymarch
