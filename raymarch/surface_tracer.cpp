#include "raymarch/surface_tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/sph_kernel.h"
#include "raymarch/bundle_gather.h"
#include "raymarch/implicit_field.h"
#include "raymarch/sphere_scene.h"

namespace twinrender::raymarch {

namespace {

// One ray's state while its bundle marches.
struct MarchRay {
    core::Ray ray;
    double t = 0.0;        // where the next segment starts
    double tEnd = 0.0;     // where the ray stops
    double hRef = 0.0;     // scale of the particles near t (segment length, tolerances)
    bool needEntry = true; // skip empty space to the next support sphere first
    bool active = true;
    bool hit = false;
    Crossing crossing;
};

struct BodyRange {
    glm::dvec3 lo, hi;  // support bounds
    double hMin;
};

bool boxesOverlap(const glm::dvec3& alo, const glm::dvec3& ahi, const glm::dvec3& blo, const glm::dvec3& bhi) {
    return alo.x <= bhi.x && ahi.x >= blo.x && alo.y <= bhi.y && ahi.y >= blo.y && alo.z <= bhi.z &&
           ahi.z >= blo.z;
}

}  // namespace

class SurfaceTracer::Workspace {
public:
    std::vector<Candidate> candidates[MAX_RAYS];  // per ray, in particle order
    std::vector<Candidate> merged;
    std::vector<std::uint32_t> carry[MAX_RAYS];   // per hit: spheres containing hit.outside
    std::vector<BundleHit> bundleHits;
    RayField field;
    MarchRay rays[MAX_RAYS];
    TraceCounters counters;
};

struct SurfaceTracer::Impl {
    const core::Camera& camera;
    const core::SceneParticles& particles;
    Settings settings;
    std::vector<float> supportRadius, margin;
    std::unique_ptr<SphereScene> support;  // support spheres (entries)
    std::unique_ptr<SphereScene> spheres;  // plain spheres (spheres mode)
    std::unique_ptr<BundleGather> bundles; // support spheres grown by the margin
    std::vector<BodyRange> bodyRanges;
    double sinBlock = 0.0;

    Impl(const EmbreeDevice& device, const core::Camera& cam, const core::SceneParticles& p,
         const Settings& st)
        : camera(cam), particles(p), settings(st) {
        const auto& ps = p.particles;
        const std::size_t n = ps.size();
        // A ray of a pixel block is at most sinBlock away from the block's central ray per unit
        // of distance from the camera (pixel angles are largest at the image centre).
        const double pixelAngle = 2.0 * cam.tanHalfFovY() / cam.height();
        sinBlock = std::min(1.0, 1.02 * (BLOCK / std::sqrt(2.0)) * pixelAngle);
        if (st.spheres) {
            std::vector<float> radii(n);
            for (std::size_t i = 0; i < n; ++i) radii[i] = static_cast<float>(st.sphereRadius) * ps.h[i];
            spheres = std::make_unique<SphereScene>(device, ps.position, radii);
            return;
        }
        supportRadius.resize(n);
        margin.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            supportRadius[i] = static_cast<float>(core::M4_SUPPORT) * ps.h[i];
            // Near particle i a camera ray of the block passes within
            // (|x_i - camera| + 2h) sinBlock of the central ray; a shadow ray of a bundle
            // within SHADOW_MARGIN h (checked per bundle).
            const double primary =
                (glm::length(glm::dvec3(ps.position[i]) - cam.position()) + supportRadius[i]) * sinBlock;
            margin[i] = static_cast<float>(std::max(primary, SHADOW_MARGIN * ps.h[i]));
        }
        support = std::make_unique<SphereScene>(device, ps.position, supportRadius);
        bundles = std::make_unique<BundleGather>(device, ps.position, supportRadius, margin);
        for (const auto& b : p.bodies) {
            BodyRange r{glm::dvec3(INFINITY), glm::dvec3(-INFINITY), INFINITY};
            for (std::size_t i = b.begin; i < b.end; ++i) {
                const double s = supportRadius[i];
                r.lo = glm::min(r.lo, glm::dvec3(ps.position[i]) - s);
                r.hi = glm::max(r.hi, glm::dvec3(ps.position[i]) + s);
                r.hMin = std::min(r.hMin, double(ps.h[i]));
            }
            bodyRanges.push_back(r);
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

    bool candidateFor(const core::Ray& ray, std::uint32_t prim, Candidate& c) const {
        const auto& ps = particles.particles;
        const double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
        const double d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
        const double x[3] = {ps.position[prim].x, ps.position[prim].y, ps.position[prim].z};
        return makeCandidate(o, d, x, ps.h[prim], ps.volume[prim], prim, c);
    }

    // Merges ray i's bundle hits into its candidates (both in particle order), dropping the
    // candidates that ended before r.t.
    void updateCandidates(int i, MarchRay& r, Workspace& w) const {
        std::vector<Candidate>& cur = w.candidates[i];
        std::vector<Candidate>& out = w.merged;
        out.clear();
        const std::uint32_t bit = 1u << i;
        std::size_t a = 0;
        for (const BundleHit& bh : w.bundleHits) {
            if (!(bh.mask & bit)) continue;
            while (a < cur.size() && cur[a].index < bh.prim) {
                if (cur[a].t1 > r.t) out.push_back(cur[a]);
                ++a;
            }
            if (a < cur.size() && cur[a].index == bh.prim) continue;  // carried already
            Candidate c;
            if (candidateFor(r.ray, bh.prim, c) && c.t1 > r.t) {
                out.push_back(c);
                ++w.counters.candidates;
            }
        }
        for (; a < cur.size(); ++a)
            if (cur[a].t1 > r.t) out.push_back(cur[a]);
        std::swap(cur, out);
    }

    // Marches the rays of w.rays[0, n) to their first crossing. Primary bundles pass the
    // block's central direction; shadow bundles (parallel rays) pass their direction too.
    void march(int n, const glm::dvec3& centralDirection, bool parallel, Workspace& w) const {
        const double segmentLength = settings.segmentLength;
        const auto& ps = particles.particles;
        for (int round = 0;; ++round) {
            // Entries: skip empty space with one closest-hit query per ray that needs it.
            int active = 0;
            for (int i = 0; i < n; ++i) {
                MarchRay& r = w.rays[i];
                if (!r.active) continue;
                if (r.needEntry) {
                    SphereScene::Hit h;
                    if (!support->closestHit(glm::vec3(r.ray.origin), glm::vec3(r.ray.direction),
                                             static_cast<float>(r.t), static_cast<float>(r.tEnd), h)) {
                        r.active = false;
                        continue;
                    }
                    // Embree's float t may land a little after the true entry: back off so
                    // that the segment starts outside every support sphere.
                    r.hRef = ps.h[h.prim];
                    r.t = std::max(r.t, double(h.t) - 1e-3 * r.hRef);
                    w.candidates[i].clear();
                    r.needEntry = false;
                }
                ++active;
            }
            if (active == 0) return;

            // The bundle: every active ray's next segment.
            RayBundle bundle;
            bundle.count = n;
            double segEnd[MAX_RAYS];
            glm::dvec3 lo(INFINITY), hi(-INFINITY), originSum(0.0);
            for (int i = 0; i < n; ++i) {
                MarchRay& r = w.rays[i];
                if (!r.active) {
                    bundle.set(i, r.ray.origin, r.ray.direction, 1.0, 0.0);  // empty interval
                    continue;
                }
                segEnd[i] = std::min(r.t + segmentLength * r.hRef, r.tEnd);
                bundle.set(i, r.ray.origin, r.ray.direction, r.t, segEnd[i]);
                const glm::dvec3 a = r.ray.origin + r.t * r.ray.direction;
                const glm::dvec3 b = r.ray.origin + segEnd[i] * r.ray.direction;
                lo = glm::min(lo, glm::min(a, b));
                hi = glm::max(hi, glm::max(a, b));
                originSum += r.ray.origin;
            }
            // The central line: through the mean origin (the camera, for primary rays).
            const glm::dvec3 origin = originSum / double(active);
            bool together = true;
            if (parallel) {
                // Parallel rays stay at their origin's offset from the central line: it must
                // be within the margin of every particle they may meet.
                double hMin = INFINITY;
                for (const auto& b : bodyRanges)
                    if (boxesOverlap(lo, hi, b.lo, b.hi)) hMin = std::min(hMin, b.hMin);
                for (int i = 0; i < n && together; ++i) {
                    if (!w.rays[i].active) continue;
                    const glm::dvec3 off = w.rays[i].ray.origin - origin;
                    const glm::dvec3 perp = off - glm::dot(off, centralDirection) * centralDirection;
                    together = glm::length(perp) <= SHADOW_MARGIN * hMin * 0.999;
                }
            }
            w.bundleHits.clear();
            if (together) {
                double tnear = INFINITY, tfar = -INFINITY;
                for (int i = 0; i < n; ++i) {
                    const MarchRay& r = w.rays[i];
                    if (!r.active) continue;
                    for (double t : {r.t, segEnd[i]}) {
                        const double along =
                            glm::dot(r.ray.origin + t * r.ray.direction - origin, centralDirection);
                        tnear = std::min(tnear, along);
                        tfar = std::max(tfar, along);
                    }
                }
                // Shift the central origin so that its range starts at 0.
                const double shift = std::min(tnear, 0.0);
                const glm::dvec3 o = origin + shift * centralDirection;
                const double slack = 1e-6 * std::max(std::abs(tfar - shift), 1.0);
                bundles->gather(bundle, o, centralDirection, tnear - shift - slack, tfar - shift + slack,
                                w.bundleHits);
                ++w.counters.bundles;
            } else {
                // Too spread out: each ray on its own (its own line is the central line).
                for (int i = 0; i < n; ++i) {
                    const MarchRay& r = w.rays[i];
                    if (!r.active) continue;
                    RayBundle one;
                    one.count = 1;
                    one.set(0, r.ray.origin, r.ray.direction, r.t, segEnd[i]);
                    const std::size_t before = w.bundleHits.size();
                    bundles->gather(one, r.ray.origin, r.ray.direction, r.t, segEnd[i], w.bundleHits);
                    for (std::size_t k = before; k < w.bundleHits.size(); ++k) w.bundleHits[k].mask = 1u << i;
                    ++w.counters.bundles;
                }
            }
            // Particle order, once per round: the merge and the summation order rely on it.
            std::sort(w.bundleHits.begin(), w.bundleHits.end(), [](const BundleHit& a, const BundleHit& b) {
                return a.prim < b.prim || (a.prim == b.prim && a.mask < b.mask);
            });
            // Combine duplicates (the per-ray fallback can report a particle for several rays).
            std::size_t k = 0;
            for (std::size_t j = 0; j < w.bundleHits.size(); ++j) {
                if (k > 0 && w.bundleHits[k - 1].prim == w.bundleHits[j].prim)
                    w.bundleHits[k - 1].mask |= w.bundleHits[j].mask;
                else
                    w.bundleHits[k++] = w.bundleHits[j];
            }
            w.bundleHits.resize(k);

            for (int i = 0; i < n; ++i) {
                MarchRay& r = w.rays[i];
                if (!r.active) continue;
                updateCandidates(i, r, w);
                ++w.counters.segments;
                std::vector<Candidate>& cands = w.candidates[i];
                if (!cands.empty()) {
                    w.field.assign(cands, r.t);
                    r.crossing = findFirstCrossing(w.field, r.t, segEnd[i], crossingSettings(r.hRef));
                    w.counters.evaluations += r.crossing.evaluations;
                    switch (r.crossing.status) {
                        case Crossing::Status::Hit:
                        case Crossing::Status::Inside:
                            r.hit = true;
                            r.active = false;
                            continue;
                        case Crossing::Status::Unresolved:
                            ++w.counters.unresolved;
                            r.active = false;
                            continue;
                        case Crossing::Status::Miss:
                            break;
                    }
                }
                r.t = segEnd[i];
                if (r.t >= r.tEnd) {
                    r.active = false;
                    continue;
                }
                // The next segment's scale: the particles that reach past this one. None:
                // empty space follows, skip it.
                double hNear = 0.0;
                for (const auto& c : cands)
                    if (c.t0 <= r.t && c.t1 > r.t) hNear = std::max(hNear, 1.0 / c.invH);
                if (hNear > 0.0) r.hRef = hNear;
                else r.needEntry = true;
            }
        }
    }

    // Analytic normal and kernel-weighted attributes at a surface point, from the candidates
    // whose support contains it (those with t0 < t < t1 on the ray that found it).
    void surfaceAttributes(const glm::dvec3& p, double t, const std::vector<Candidate>& cands,
                           SurfaceHit& hit) const {
        const auto& ps = particles.particles;
        struct Weighted {
            std::uint32_t index;
            double w;
        };
        thread_local std::vector<Weighted> near;
        near.clear();
        glm::dvec3 grad(0.0);
        // The visible body: the one with the largest summed weight (a few bodies at most).
        std::uint32_t ids[8];
        double sums[8];
        int bodies = 0;
        for (const auto& c : cands) {
            if (!(c.t0 < t && c.t1 > t)) continue;
            const glm::dvec3 r = p - glm::dvec3(ps.position[c.index]);
            const double q = std::sqrt(glm::dot(r, r)) * c.invH;
            if (q >= core::M4_SUPPORT) continue;
            const double w = c.coef * core::m4Shape(q);
            if (q > 0.0) grad += r * (c.coef * core::m4ShapeDerivative(q) * c.invH * c.invH / q);
            near.push_back({c.index, w});
            const std::uint32_t b = ps.body[c.index];
            int k = 0;
            while (k < bodies && ids[k] != b) ++k;
            if (k == bodies && bodies < 8) {
                ids[bodies] = b;
                sums[bodies++] = 0.0;
            }
            if (k < bodies) sums[k] += w;
        }
        int bestK = 0;
        for (int k = 1; k < bodies; ++k)
            if (sums[k] > sums[bestK]) bestK = k;
        const std::uint32_t best = bodies > 0 ? ids[bestK] : 0;
        const double g = glm::length(grad);
        hit.normal = g > 0.0 ? glm::vec3(-grad / g) : glm::vec3(0.0f);
        // uv and glow: normalised kernel weights over the visible body's particles; u is
        // unwrapped around the heaviest particle's u so the seam does not average to 0.5.
        double uRef = 0.0, wMax = -1.0;
        for (const auto& [index, w] : near)
            if (ps.body[index] == best && w > wMax) {
                wMax = w;
                uRef = ps.uv[index].x;
            }
        double wsum = 0.0;
        glm::dvec2 uv(0.0);
        glm::dvec3 glow(0.0);
        for (const auto& [index, w] : near) {
            if (ps.body[index] != best) continue;
            const glm::vec2 puv = ps.uv[index];
            uv += w * glm::dvec2(puv.x - std::round(puv.x - uRef), puv.y);
            glow += w * glm::dvec3(ps.glow[index]);
            wsum += w;
        }
        if (wsum > 0.0) {
            uv /= wsum;
            glow /= wsum;
        }
        uv.x -= std::floor(uv.x);
        hit.uv = glm::vec2(uv);
        hit.glow = glm::vec3(glow);
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

    // Distance from p along dir to the exit of the scene bounds (no surface lies beyond).
    double exitDistance(const glm::dvec3& p, const glm::dvec3& dir) const {
        const glm::dvec3 lo = particles.boundsMin, hi = particles.boundsMax;
        double tExit = 0.0;
        for (int k = 0; k < 3; ++k)
            if (dir[k] != 0.0) tExit = std::max(tExit, ((dir[k] > 0.0 ? hi[k] : lo[k]) - p[k]) / dir[k]);
        return tExit + 1e-6 * glm::length(hi - lo);
    }
};

SurfaceTracer::SurfaceTracer(const EmbreeDevice& device, const core::Camera& camera,
                             const core::SceneParticles& particles, const Settings& settings) {
    const auto start = std::chrono::steady_clock::now();
    mImpl = std::make_unique<Impl>(device, camera, particles, settings);
    mBuildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

SurfaceTracer::~SurfaceTracer() = default;

SurfaceTracer::WorkspacePtr SurfaceTracer::makeWorkspace() const { return WorkspacePtr(new Workspace()); }

void SurfaceTracer::WorkspaceDeleter::operator()(Workspace* w) const { delete w; }

const TraceCounters& SurfaceTracer::counters(const Workspace& w) const { return w.counters; }
void SurfaceTracer::resetCounters(Workspace& w) const { w.counters = {}; }

void SurfaceTracer::tracePrimary(int n, const core::Ray* rays, const double* tnear, const double* tfar,
                                 const core::Ray& central, SurfaceHit* hits, bool* found,
                                 Workspace& w) const {
    const Impl& im = *mImpl;
    if (im.settings.spheres) {
        for (int i = 0; i < n; ++i) found[i] = im.traceSphere(rays[i], tnear[i], tfar[i], hits[i]);
        return;
    }
    for (int i = 0; i < n; ++i) {
        MarchRay& r = w.rays[i];
        r = MarchRay{};
        r.ray = rays[i];
        r.t = tnear[i];
        r.tEnd = tfar[i];
    }
    im.march(n, central.direction, false, w);
    for (int i = 0; i < n; ++i) {
        const MarchRay& r = w.rays[i];
        found[i] = r.hit;
        w.carry[i].clear();
        if (!r.hit) continue;
        SurfaceHit& hit = hits[i];
        hit.t = r.crossing.t;
        hit.position = r.ray.origin + r.crossing.t * r.ray.direction;
        hit.outside = r.ray.origin + r.crossing.tBelow * r.ray.direction;
        double hMin = INFINITY;
        for (const auto& c : w.candidates[i]) {
            if (c.t0 < r.crossing.t && c.t1 > r.crossing.t) hMin = std::min(hMin, 1.0 / c.invH);
            if (c.t0 < r.crossing.tBelow && c.t1 > r.crossing.tBelow) w.carry[i].push_back(c.index);
        }
        hit.hRef = std::isfinite(hMin) ? hMin : r.hRef;
        im.surfaceAttributes(hit.position, r.crossing.t, w.candidates[i], hit);
    }
}

void SurfaceTracer::traceShadows(int n, const SurfaceHit* hits, const bool* found,
                                 const glm::dvec3& toLight, float* visibility, Workspace& w) const {
    const Impl& im = *mImpl;
    bool traced[MAX_RAYS] = {};
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
            visibility[i] = im.spheres->occluded(glm::vec3(hit.outside), glm::vec3(toLight), 0.0f,
                                                 static_cast<float>(im.exitDistance(hit.outside, toLight)))
                                ? 0.0f
                                : 1.0f;
            continue;
        }
        r.ray = core::Ray{hit.outside, toLight};
        r.t = 2.0 * im.settings.rootTolerance * hit.hRef;
        r.tEnd = im.exitDistance(hit.outside, toLight);
        r.hRef = hit.hRef;
        r.needEntry = false;
        r.active = true;
        traced[i] = true;
        // The spheres that contain the origin, handed over by the primary ray (in particle
        // order), re-expressed along the shadow ray.
        w.candidates[i].clear();
        for (std::uint32_t prim : w.carry[i]) {
            Candidate c;
            if (im.candidateFor(r.ray, prim, c) && c.t1 > r.t) w.candidates[i].push_back(c);
        }
    }
    if (!im.settings.spheres) im.march(n, toLight, true, w);
    for (int i = 0; i < n; ++i)
        if (traced[i]) visibility[i] = w.rays[i].hit ? 0.0f : 1.0f;
}

}  // namespace twinrender::raymarch
