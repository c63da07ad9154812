#include "raymarch/renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>
#include <pmmintrin.h>

#include "core/shading.h"
#include "core/sph_kernel.h"
#include "raymarch/bundle_gather.h"
#include "raymarch/implicit_field.h"
#include "raymarch/sphere_scene.h"

namespace twinrender::raymarch {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::string cpuName() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) {
            auto colon = line.find(':');
            if (colon != std::string::npos) return line.substr(colon + 2);
        }
    return "CPU";
}

// Per-thread scratch memory: nothing is allocated in the hot loop once it has grown.
struct Scratch {
    std::vector<std::uint32_t> prims;
    std::vector<BundleHit> bundleHits;
    // Per ray of a block: the particles whose support contains the hit's outside point, the
    // spheres its shadow ray starts inside of.
    std::vector<std::uint32_t> carryPrims[RayBundle::MAX_RAYS];
    std::vector<Candidate> candidates;
    std::vector<std::uint32_t> stamp;  // per particle: the last gather that saw it
    std::uint32_t stampId = 0;
    // Counters, summed at the end.
    std::uint64_t unresolved = 0;
    std::uint64_t gathered = 0;
    std::uint64_t evaluations = 0;
    std::uint64_t segments = 0;
};

// Deterministic per-sample jitter in [0, 1).
float hashToUnit(std::uint32_t x, std::uint32_t y, std::uint32_t k, std::uint32_t dim) {
    std::uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ k * 0xcb1ab31fu ^ dim * 0x165667b1u;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return (h >> 8) * (1.0f / 16777216.0f);
}

struct BodyRange {
    glm::dvec3 lo, hi;  // support bounds
    double hMax;
};

}  // namespace

struct Renderer::Impl {
    const EmbreeDevice& device;
    const core::Scene& scene;
    const core::SceneParticles& particles;
    const std::vector<core::Material>& materials;
    Settings settings;
    core::Camera camera;
    std::unique_ptr<SphereScene> support;  // spheres of radius 2h (implicit surface)
    std::unique_ptr<SphereScene> spheres;  // plain spheres (spheres mode)
    std::unique_ptr<BundleGather> bundles; // support spheres grown by the pixel-block margin
    std::vector<float> supportRadius, bundleMargin;
    std::vector<BodyRange> bodyRanges;
    double buildMs = 0.0;
    mutable tbb::enumerable_thread_specific<Scratch> scratch;

    Impl(const EmbreeDevice& d, const core::Scene& s, const core::SceneParticles& p,
         const std::vector<core::Material>& m, const Settings& st)
        : device(d), scene(s), particles(p), materials(m), settings(st), camera(s.camera) {
        const auto& ps = p.particles;
        const auto start = Clock::now();
        std::vector<float> radii(ps.size());
        const float scale = st.spheres ? static_cast<float>(st.sphereRadius) : float(core::M4_SUPPORT);
        for (std::size_t i = 0; i < ps.size(); ++i) radii[i] = scale * ps.h[i];
        if (st.spheres) {
            spheres = std::make_unique<SphereScene>(d, ps.position, radii);
        } else {
            support = std::make_unique<SphereScene>(d, ps.position, radii);
            // A ray of a pixel block is at most sinBlock away (per unit of distance from the
            // camera) from the block's central ray; near particle i that is at most
            // (|x_i - camera| + 2h) sinBlock.
            const double sinBlock = blockSpread();
            supportRadius = radii;
            bundleMargin.resize(ps.size());
            for (std::size_t i = 0; i < ps.size(); ++i)
                bundleMargin[i] = static_cast<float>(
                    (glm::length(glm::dvec3(ps.position[i]) - camera.position()) + radii[i]) * sinBlock);
            bundles = std::make_unique<BundleGather>(d, ps.position, supportRadius, bundleMargin);
        }
        buildMs = msSince(start);
        for (const auto& b : p.bodies) {
            BodyRange r{glm::dvec3(INFINITY), glm::dvec3(-INFINITY), 0.0};
            for (std::size_t i = b.begin; i < b.end; ++i) {
                const double support2 = core::M4_SUPPORT * ps.h[i];
                r.lo = glm::min(r.lo, glm::dvec3(ps.position[i]) - support2);
                r.hi = glm::max(r.hi, glm::dvec3(ps.position[i]) + support2);
                r.hMax = std::max(r.hMax, double(ps.h[i]));
            }
            bodyRanges.push_back(r);
        }
    }

    // Starts a new ray: particles seen before count as unseen again.
    static void beginRay(Scratch& s, std::size_t particleCount) {
        if (s.stamp.size() != particleCount) s.stamp.assign(particleCount, 0);
        if (++s.stampId == 0) {
            std::fill(s.stamp.begin(), s.stamp.end(), 0);
            s.stampId = 1;
        }
    }

    // Adds the particle to the ray's candidates unless it was seen on this ray already.
    void addCandidate(const core::Ray& ray, std::uint32_t prim, Scratch& s) const {
        if (s.stamp[prim] == s.stampId) return;
        s.stamp[prim] = s.stampId;
        const auto& ps = particles.particles;
        const double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
        const double d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
        const double c[3] = {ps.position[prim].x, ps.position[prim].y, ps.position[prim].z};
        Candidate cand;
        if (makeCandidate(o, d, c, ps.h[prim], ps.volume[prim], prim, cand)) {
            s.candidates.push_back(cand);
            ++s.gathered;
        }
    }

    // Extends the ray's candidates to every support sphere that overlaps [ta, tb], given that
    // s.candidates already holds every sphere that contains the point at ta. Embree reports
    // the spheres entered in [ta, tb] (and, redundantly, the exits of those containing ta).
    // Candidates that ended before ta are dropped; the rest are sorted by (t0, index), so
    // the summation order, and the image, do not depend on the traversal order.
    void gatherCandidates(const core::Ray& ray, double ta, double tb, Scratch& s) const {
        std::erase_if(s.candidates, [&](const Candidate& c) { return c.t1 <= ta; });
        s.prims.clear();
        support->gather(glm::vec3(ray.origin + ta * ray.direction), glm::vec3(ray.direction), 0.0f,
                        static_cast<float>(tb - ta), s.prims);
        for (std::uint32_t prim : s.prims) addCandidate(ray, prim, s);
        std::sort(s.candidates.begin(), s.candidates.end(), [](const Candidate& x, const Candidate& y) {
            return x.t0 < y.t0 || (x.t0 == y.t0 && x.index < y.index);
        });
    }

    enum class Trace { Miss, Hit, Unresolved };

    // Marches the implicit surface from tStart. With `jump`, empty space up to the first
    // support sphere is skipped with one Embree query; without it, s.candidates must already
    // hold every support sphere that contains the point at tStart (beginRay called). On a hit,
    // s.candidates holds the candidates around it.
    Trace traceImplicit(const core::Ray& ray, double tStart, double tEnd, bool jump, double hRef,
                        Crossing& crossing, Scratch& s) const {
        const auto& ps = particles.particles;
        double t = tStart;
        bool needEntry = jump;
        while (t < tEnd) {
            if (needEntry) {
                SphereScene::Hit h;
                if (!support->closestHit(glm::vec3(ray.origin), glm::vec3(ray.direction),
                                         static_cast<float>(t), static_cast<float>(tEnd), h))
                    return Trace::Miss;
                // Embree's float t may land a little after the true entry: back off so that
                // the segment starts outside every support sphere.
                t = std::max(t, double(h.t) - 1e-3 * ps.h[h.prim]);
                hRef = ps.h[h.prim];
                s.candidates.clear();
                needEntry = false;
            }
            const double segEnd = std::min(t + settings.segmentLength * hRef, tEnd);
            gatherCandidates(ray, t, segEnd, s);
            ++s.segments;
            if (s.candidates.empty()) {
                t = segEnd;
                needEntry = true;
                continue;
            }
            crossing = findFirstCrossing(s.candidates, t, segEnd, crossingSettings(hRef));
            s.evaluations += crossing.evaluations;
            switch (crossing.status) {
                case Crossing::Status::Hit:
                case Crossing::Status::Inside:
                    return Trace::Hit;
                case Crossing::Status::Unresolved:
                    ++s.unresolved;
                    return Trace::Unresolved;
                case Crossing::Status::Miss:
                    break;
            }
            t = segEnd;
            // The scale of the next segment: the particles that reach past this one.
            double hNear = 0.0;
            for (const auto& c : s.candidates)
                if (c.t1 > t && c.t0 <= t) hNear = std::max(hNear, 1.0 / c.invH);
            if (hNear > 0.0) hRef = hNear;
            else needEntry = true;
        }
        return Trace::Miss;
    }

    // Analytic normal and kernel-weighted attributes at a surface point.
    void surfaceAttributes(const glm::dvec3& p, const std::vector<Candidate>& cands,
                           SurfaceHit& hit) const {
        const auto& ps = particles.particles;
        glm::dvec3 grad(0.0);
        // The visible body: the one with the largest summed weight.
        std::uint32_t bestBody = 0;
        {
            // Few bodies: a small linear table keeps this allocation-free.
            std::uint32_t ids[8];
            double sums[8];
            int n = 0;
            double bestSum = -1.0;
            for (const auto& c : cands) {
                const glm::dvec3 x = glm::dvec3(ps.position[c.index]);
                const glm::dvec3 r = p - x;
                const double q = std::sqrt(glm::dot(r, r)) * c.invH;
                if (q >= core::M4_SUPPORT) continue;
                const double w = c.coef * core::m4Shape(q);
                if (q > 0.0) grad += r * (c.coef * core::m4ShapeDerivative(q) * c.invH * c.invH / q);
                const std::uint32_t b = ps.body[c.index];
                int k = 0;
                while (k < n && ids[k] != b) ++k;
                if (k == n && n < 8) {
                    ids[n] = b;
                    sums[n++] = 0.0;
                }
                if (k < n) sums[k] += w;
                if (k < n && sums[k] > bestSum) {
                    bestSum = sums[k];
                    bestBody = b;
                }
            }
        }
        const double g = glm::length(grad);
        hit.normal = g > 0.0 ? glm::vec3(-grad / g) : glm::vec3(0.0f);
        // uv, glow: normalised kernel weights over the visible body's particles; u unwrapped
        // around the heaviest particle's u so that the seam does not average to 0.5.
        double wsum = 0.0, uRef = -1.0, wMax = -1.0;
        glm::dvec2 uv(0.0);
        glm::dvec3 glow(0.0);
        for (int pass = 0; pass < 2; ++pass)
            for (const auto& c : cands) {
                if (ps.body[c.index] != bestBody) continue;
                const glm::dvec3 r = p - glm::dvec3(ps.position[c.index]);
                const double q = std::sqrt(glm::dot(r, r)) * c.invH;
                if (q >= core::M4_SUPPORT) continue;
                const double w = c.coef * core::m4Shape(q);
                const glm::vec2 puv = ps.uv[c.index];
                if (pass == 0) {
                    if (w > wMax) {
                        wMax = w;
                        uRef = puv.x;
                    }
                    continue;
                }
                const double u = puv.x - std::round(puv.x - uRef);
                uv += w * glm::dvec2(u, puv.y);
                glow += w * glm::dvec3(ps.glow[c.index]);
                wsum += w;
            }
        if (wsum > 0.0) {
            uv /= wsum;
            glow /= wsum;
        }
        uv.x -= std::floor(uv.x);
        hit.uv = glm::vec2(uv);
        hit.glow = glm::vec3(glow);
        hit.body = bestBody;
        hit.material = particles.bodies.empty() ? 0 : particles.bodies[bestBody].material;
    }

    bool traceSurface(const core::Ray& ray, double tnear, double tfar, SurfaceHit& hit,
                      Scratch& s) const {
        if (settings.spheres) return traceSpheres(ray, tnear, tfar, hit);
        Crossing crossing;
        beginRay(s, particles.particles.size());
        if (traceImplicit(ray, tnear, tfar, true, 0.0, crossing, s) != Trace::Hit) return false;
        fillHit(ray, crossing, s, hit, s.carryPrims[0]);
        return true;
    }

    bool traceSpheres(const core::Ray& ray, double tnear, double tfar, SurfaceHit& hit) const {
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
        glm::dvec2 uv = glm::dvec2(ps.uv[i]) +
                        glm::dvec2(glm::dot(glm::dvec3(ps.dudx[i]), off), glm::dot(glm::dvec3(ps.dvdx[i]), off));
        uv.x -= std::floor(uv.x);
        uv.y = std::clamp(uv.y, 0.0, 1.0);
        hit.uv = glm::vec2(uv);
        hit.body = ps.body[i];
        hit.material = ps.material[i];
        hit.glow = ps.glow[i];
        return true;
    }

    static constexpr int BLOCK = 4;  // pixel block side for bundle gathers

    // Upper bound of the sine of the angle between a block's central ray and any of its rays
    // (samples anywhere inside the block's pixels), with 2 % to spare.
    double blockSpread() const {
        const double pixelAngle = 2.0 * camera.tanHalfFovY() / camera.height();  // largest at the centre
        return std::min(1.0, 1.02 * (BLOCK / std::sqrt(2.0)) * pixelAngle);
    }

    // Primary rays of one pixel block: the entry of each ray by a closest-hit query, the first
    // segment of every ray from one bundle gather, and the per-ray march after that.
    void traceBlock(const core::Ray* rays, const double* tnear, const double* tfar, int n,
                    const core::Ray& central, SurfaceHit* hits, bool* found, Scratch& s) const {
        const auto& ps = particles.particles;
        RayBundle bundle;
        bundle.count = n;
        double hRef[RayBundle::MAX_RAYS], segStart[RayBundle::MAX_RAYS], segEnd[RayBundle::MAX_RAYS];
        double lo = INFINITY, hi = 0.0;
        bool any = false;
        for (int i = 0; i < n; ++i) {
            found[i] = false;
            SphereScene::Hit h;
            const bool entered = support->closestHit(glm::vec3(rays[i].origin), glm::vec3(rays[i].direction),
                                                     static_cast<float>(tnear[i]), static_cast<float>(tfar[i]), h);
            if (!entered) {
                bundle.set(i, rays[i].origin, rays[i].direction, 1.0, 0.0);  // empty interval
                continue;
            }
            hRef[i] = ps.h[h.prim];
            const double t0 = std::max(tnear[i], double(h.t) - 1e-3 * hRef[i]);
            const double t1 = std::min(t0 + settings.segmentLength * hRef[i], tfar[i]);
            segStart[i] = t0;
            segEnd[i] = t1;
            bundle.set(i, rays[i].origin, rays[i].direction, t0, t1);
            lo = std::min(lo, t0);
            hi = std::max(hi, t1);
            any = true;
        }
        if (!any) return;
        // The central ray's parameter of a point on ray i differs by the cosine between them.
        const double cosMin = std::sqrt(std::max(0.0, 1.0 - blockSpread() * blockSpread()));
        s.bundleHits.clear();
        bundles->gather(bundle, central.origin, central.direction, lo * cosMin * (1.0 - 1e-6),
                        hi * (1.0 + 1e-6), s.bundleHits);
        for (int i = 0; i < n; ++i) {
            if (!(bundle.tMin[i] <= bundle.tMax[i])) continue;
            const core::Ray& ray = rays[i];
            beginRay(s, ps.size());
            s.candidates.clear();
            for (const BundleHit& bh : s.bundleHits)
                if (bh.mask & (1u << i)) addCandidate(ray, bh.prim, s);
            const double t0 = segStart[i], t1 = segEnd[i];
            // Spheres that open after t1 stay: the march past t1 needs them (they are marked
            // as seen on this ray and will not be gathered again).
            std::erase_if(s.candidates, [&](const Candidate& c) { return c.t1 <= t0; });
            std::sort(s.candidates.begin(), s.candidates.end(), [](const Candidate& x, const Candidate& y) {
                return x.t0 < y.t0 || (x.t0 == y.t0 && x.index < y.index);
            });
            ++s.segments;
            Crossing crossing;
            Trace result = Trace::Miss;
            if (!s.candidates.empty()) {
                crossing = findFirstCrossing(s.candidates, t0, t1, crossingSettings(hRef[i]));
                s.evaluations += crossing.evaluations;
                if (crossing.status == Crossing::Status::Hit || crossing.status == Crossing::Status::Inside)
                    result = Trace::Hit;
                else if (crossing.status == Crossing::Status::Unresolved) {
                    ++s.unresolved;
                    result = Trace::Unresolved;
                }
            }
            // No crossing in the first segment: march on, ray by ray, from its end.
            if (result == Trace::Miss && t1 < tfar[i])
                result = traceImplicit(ray, t1, tfar[i], s.candidates.empty(), hRef[i], crossing, s);
            if (result != Trace::Hit) continue;
            found[i] = true;
            fillHit(ray, crossing, s, hits[i], s.carryPrims[i]);
        }
    }

    CrossingSettings crossingSettings(double hRef) const {
        CrossingSettings cs;
        cs.level = settings.surfaceLevel;
        cs.tolerance = settings.rootTolerance * hRef;
        cs.maxStep = settings.stepWindow * hRef;
        cs.maxIterations = settings.maxIterations;
        return cs;
    }

    void fillHit(const core::Ray& ray, const Crossing& crossing, Scratch& s, SurfaceHit& hit,
                 std::vector<std::uint32_t>& carry) const {
        carry.clear();
        for (const auto& c : s.candidates)
            if (c.t0 < crossing.tBelow && c.t1 > crossing.tBelow) carry.push_back(c.index);
        hit.t = crossing.t;
        hit.outside = ray.origin + crossing.tBelow * ray.direction;
        hit.position = ray.origin + crossing.t * ray.direction;
        double hMin = INFINITY;
        for (const auto& c : s.candidates)
            if (c.t0 < crossing.t && c.t1 > crossing.t) hMin = std::min(hMin, 1.0 / c.invH);
        hit.hRef = std::isfinite(hMin) ? hMin : 1.0 / s.candidates.front().invH;
        surfaceAttributes(hit.position, s.candidates, hit);
    }

    // `carry`: the particles whose support contains hit.outside (recorded by fillHit).
    float lightVisibility(const SurfaceHit& hit, const std::vector<std::uint32_t>& carry, Scratch& s) const {
        const glm::dvec3 toLight = -scene.light.direction;
        // n = -grad(phi)/|grad(phi)|: with n.l <= 0 the ray toward the light enters the
        // surface at once (dphi/dt >= 0), so the point is occluded; no ray is needed.
        if (glm::dot(glm::dvec3(hit.normal), toLight) <= 0.0) return 0.0f;
        const glm::dvec3 origin = hit.outside;
        const core::Ray ray{origin, toLight};
        // Leave the scene bounds: no surface lies beyond them.
        const glm::dvec3 lo = particles.boundsMin, hi = particles.boundsMax;
        double tExit = 0.0;
        for (int k = 0; k < 3; ++k) {
            if (toLight[k] == 0.0) continue;
            const double t = ((toLight[k] > 0.0 ? hi[k] : lo[k]) - origin[k]) / toLight[k];
            tExit = std::max(tExit, t);
        }
        tExit = std::max(tExit, 0.0) + 1e-6 * glm::length(hi - lo);
        if (settings.spheres)
            return spheres->occluded(glm::vec3(origin), glm::vec3(toLight), 0.0f,
                                     static_cast<float>(tExit))
                       ? 0.0f
                       : 1.0f;
        // The spheres that contain the origin are among the primary ray's candidates around
        // the hit (s.candidates): carry them over, re-expressed along the shadow ray.
        s.candidates.clear();
        beginRay(s, particles.particles.size());
        for (std::uint32_t prim : carry) addCandidate(ray, prim, s);
        Crossing crossing;
        const double start = 2.0 * settings.rootTolerance * hit.hRef;
        return traceImplicit(ray, start, tExit, false, hit.hRef, crossing, s) == Trace::Hit ? 0.0f
                                                                                             : 1.0f;
    }
};

Renderer::Renderer(const EmbreeDevice& device, const core::Scene& scene,
                   const core::SceneParticles& particles, const std::vector<core::Material>& materials,
                   const Settings& settings)
    : mImpl(std::make_unique<Impl>(device, scene, particles, materials, settings)) {}

Renderer::~Renderer() = default;

bool Renderer::traceSurface(const core::Ray& ray, double tnear, double tfar, SurfaceHit& hit) const {
    return mImpl->traceSurface(ray, tnear, tfar, hit, mImpl->scratch.local());
}

float Renderer::lightVisibility(const SurfaceHit& hit) const {
    // The single-ray API: the hit came from traceSurface on this thread, which left its
    // carry set in slot 0.
    Scratch& s = mImpl->scratch.local();
    return mImpl->lightVisibility(hit, s.carryPrims[0], s);
}

core::Frame Renderer::render(const std::function<void(double)>& progress) const {
    const Impl& im = *mImpl;
    const Settings& st = im.settings;
    const int width = im.camera.width(), height = im.camera.height();
    const int tile = st.tileSize;
    const int tilesX = (width + tile - 1) / tile, tilesY = (height + tile - 1) / tile;
    const int tileCount = tilesX * tilesY;
    core::Frame frame;
    frame.renderer = "raymarch";
    frame.image = core::aov::makeImage(width, height);
    frame.particleCount = im.particles.particles.size();
    core::Image& img = frame.image;
    const int cR = img.channelIndex("R"), cA = img.channelIndex("A"), cZ = img.channelIndex("Z"),
              cN = img.channelIndex("N.X"), cU = img.channelIndex("uv.U"), cId = img.channelIndex("id"),
              cE = img.channelIndex("emission.R"), cS = img.channelIndex("shadow");
    const double nearT = im.scene.camera.near, farT = im.scene.camera.far;
    const int grid = static_cast<int>(std::ceil(std::sqrt(double(st.spp))));
    std::atomic<int> done{0};
    const auto start = Clock::now();
    std::atomic<std::int64_t> shadowNs{0}, primaryNs{0};

    tbb::parallel_for(tbb::blocked_range<int>(0, tileCount, 1), [&](const tbb::blocked_range<int>& range) {
        // Embree wants flush-to-zero and denormals-are-zero on every thread that traces.
        _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
        _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
        Scratch& s = im.scratch.local();
        constexpr int B = Impl::BLOCK;
        constexpr int N = B * B;
        for (int ti = range.begin(); ti != range.end(); ++ti) {
            const int tx0 = (ti % tilesX) * tile, ty0 = (ti / tilesX) * tile;
            std::int64_t tPrimary = 0, tShadow = 0;
            for (int by = ty0; by < std::min(ty0 + tile, height); by += B)
                for (int bx = tx0; bx < std::min(tx0 + tile, width); bx += B) {
                    // Per pixel of the block, summed over its samples.
                    int px[N], py[N], n = 0;
                    for (int y = by; y < std::min(by + B, height); ++y)
                        for (int x = bx; x < std::min(bx + B, width); ++x) {
                            px[n] = x;
                            py[n] = y;
                            ++n;
                        }
                    glm::dvec3 beauty[N], emission[N];  // glm does not zero them
                    std::fill_n(beauty, N, glm::dvec3(0.0));
                    std::fill_n(emission, N, glm::dvec3(0.0));
                    double coverage[N] = {}, shadow[N] = {}, bestDist[N];
                    std::fill_n(bestDist, N, INFINITY);
                    const core::Ray central = im.camera.ray(bx + 0.5 * B, by + 0.5 * B);
                    for (int k = 0; k < st.spp; ++k) {
                        core::Ray rays[N];
                        double tnear[N], tfar[N], cosAxis[N], jx[N], jy[N];
                        for (int i = 0; i < n; ++i) {
                            jx[i] = jy[i] = 0.5;
                            if (st.spp > 1) {
                                jx[i] = ((k % grid) + hashToUnit(px[i], py[i], k, 0)) / grid;
                                jy[i] = ((k / grid) + hashToUnit(px[i], py[i], k, 1)) / grid;
                            }
                            rays[i] = im.camera.ray(px[i] + jx[i], py[i] + jy[i]);
                            cosAxis[i] = glm::dot(rays[i].direction, im.camera.forward());
                            tnear[i] = nearT / cosAxis[i];
                            tfar[i] = farT / cosAxis[i];
                        }
                        SurfaceHit hits[N];
                        bool found[N];
                        const auto t0 = Clock::now();
                        if (st.spheres)
                            for (int i = 0; i < n; ++i) found[i] = im.traceSpheres(rays[i], tnear[i], tfar[i], hits[i]);
                        else
                            im.traceBlock(rays, tnear, tfar, n, central, hits, found, s);
                        const auto t1 = Clock::now();
                        tPrimary += (t1 - t0).count();
                        for (int i = 0; i < n; ++i) {
                            if (!found[i]) continue;
                            const SurfaceHit& hit = hits[i];
                            const float vis = st.shadows ? im.lightVisibility(hit, s.carryPrims[i], s) : 1.0f;
                            core::SurfacePoint sp;
                            sp.normal = hit.normal;
                            sp.toEye = glm::vec3(-rays[i].direction);
                            sp.uv = hit.uv;
                            sp.material = hit.material;
                            sp.emission = core::surfaceEmission(im.materials[hit.material], hit.uv, hit.glow);
                            sp.visibility = vis;
                            beauty[i] += glm::dvec3(core::shade(im.materials, im.scene.light, sp));
                            emission[i] += glm::dvec3(sp.emission);
                            coverage[i] += 1.0;
                            shadow[i] += vis;
                            // Geometric channels are not filtered: they come from the hit
                            // sample nearest the pixel centre.
                            const double dist = (jx[i] - 0.5) * (jx[i] - 0.5) + (jy[i] - 0.5) * (jy[i] - 0.5);
                            if (dist < bestDist[i]) {
                                bestDist[i] = dist;
                                const int x = px[i], y = py[i];
                                img.at(x, y, cZ) = static_cast<float>(hit.t * cosAxis[i]);
                                for (int c = 0; c < 3; ++c) img.at(x, y, cN + c) = hit.normal[c];
                                img.at(x, y, cU) = hit.uv.x;
                                img.at(x, y, cU + 1) = hit.uv.y;
                                img.at(x, y, cId) = static_cast<float>(hit.body);
                            }
                        }
                        tShadow += (Clock::now() - t1).count();
                    }
                    for (int i = 0; i < n; ++i) {
                        if (coverage[i] == 0.0) continue;
                        const int x = px[i], y = py[i];
                        const double inv = 1.0 / st.spp;
                        for (int c = 0; c < 3; ++c) {
                            img.at(x, y, cR + c) = static_cast<float>(beauty[i][c] * inv);
                            img.at(x, y, cE + c) = static_cast<float>(emission[i][c] / coverage[i]);
                        }
                        img.at(x, y, cA) = static_cast<float>(coverage[i] * inv);
                        img.at(x, y, cS) = static_cast<float>(shadow[i] / coverage[i]);
                    }
                }
            primaryNs += tPrimary;
            shadowNs += tShadow;
            const int finished = ++done;
            if (progress) progress(double(finished) / tileCount);
        }
    });
    const double traceMs = msSince(start);
    // Split the parallel wall time by the thread time each kind of ray took.
    const double primary = double(primaryNs.load()), shadowT = double(shadowNs.load());
    const double sum = std::max(primary + shadowT, 1.0);
    frame.timingsMs["build"] = im.buildMs;
    frame.timingsMs["trace"] = traceMs * primary / sum;
    frame.timingsMs["shade"] = traceMs * shadowT / sum;  // shadow rays and shading
    frame.timingsMs["total"] = im.buildMs + traceMs;

    Scratch total;
    for (const Scratch& s : im.scratch) {
        total.unresolved += s.unresolved;
        total.gathered += s.gathered;
        total.evaluations += s.evaluations;
        total.segments += s.segments;
    }
    for (Scratch& s : im.scratch) s.unresolved = s.gathered = s.evaluations = s.segments = 0;
    frame.counters["unbracketed_rays"] = double(total.unresolved);
    frame.counters["segments"] = double(total.segments);
    frame.counters["candidates"] = double(total.gathered);
    frame.counters["field_evaluations"] = double(total.evaluations);
    frame.device = fmt::format("{} ({} threads)", cpuName(), tbb::this_task_arena::max_concurrency());
    frame.settings = toJson(st);
    return frame;
}

}  // namespace twinrender::raymarch
