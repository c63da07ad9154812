#include "raymarch/renderer.h"

#include <fmt/format.h>
#include <pmmintrin.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "core/atmosphere.h"
#include "core/camera.h"
#include "core/cancellation.h"
#include "core/emitters.h"
#include "core/shading.h"
#include "raymarch/ao_hemisphere.h"
#include "raymarch/emitter_cone.h"
#include "raymarch/pixel_samples.h"
#include "raymarch/progressive_strata.h"
#include "raymarch/sun_disc.h"
#include "raymarch/surface_tracer.h"

namespace twinrender::raymarch {

namespace {

using Clock = std::chrono::steady_clock;
using Workspace = SurfaceTracer::Workspace;
using Workspaces = tbb::enumerable_thread_specific<SurfaceTracer::WorkspacePtr>;

constexpr int B = SurfaceTracer::BLOCK;  // pixel block side
constexpr int N = B * B;                 // pixels per block

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

// One kind of secondary estimate (occlusion, the emitters' light, the sun's disc) over some
// hit samples: the rays it took and the standard errors it reached.
struct EstimateTally {
    std::int64_t estimates = 0;  // hit samples
    std::int64_t rays = 0;
    std::int64_t atCap = 0;  // with a target: estimates (a body's, for the emitters) that
                             // stopped at the cap with their error not below it
    double errorSum = 0.0;   // of the hit samples' standard errors
    double errorMax = 0.0;

    void add(double standardError, std::int64_t rayCount) {
        ++estimates;
        rays += rayCount;
        errorSum += standardError;
        errorMax = std::max(errorMax, standardError);
    }
    // Tallies are merged in tile order: the sum of doubles then does not depend on the threads.
    void merge(const EstimateTally& t) {
        estimates += t.estimates;
        rays += t.rays;
        atCap += t.atCap;
        errorSum += t.errorSum;
        errorMax = std::max(errorMax, t.errorMax);
    }
    // The frame's counters PREFIX_standard_error (the mean over the hit samples),
    // PREFIX_standard_error_max, PREFIX_rays, and PREFIX_at_cap with a target.
    void write(const std::string& prefix, bool target,
               std::map<std::string, double>& counters) const {
        counters[prefix + "_standard_error"] = estimates > 0 ? errorSum / double(estimates) : 0.0;
        counters[prefix + "_standard_error_max"] = errorMax;
        counters[prefix + "_rays"] = double(rays);
        if (target) counters[prefix + "_at_cap"] = double(atCap);
    }
};

// Thread time of the parts of tracing, in steady-clock ticks, and the secondary estimates'
// tallies, of one tile.
struct StageTicks {
    std::int64_t trace = 0;        // camera rays, and the shadow rays of a point sun
    std::int64_t sun = 0;          // shadow rays over the sun's disc (light.angular_radius > 0)
    std::int64_t ao = 0;           // ambient occlusion rays
    std::int64_t emissive = 0;     // rays toward the emitting bodies
    std::int64_t shade = 0;        // shading the hits
    std::int64_t atmosphere = 0;   // the atmosphere's quadrature along the camera rays
    std::int64_t primaryRays = 0;  // camera rays traced
    EstimateTally occlusion;       // the open fraction (aoStandardError without a target)
    EstimateTally light;           // the irradiance's luminance
    EstimateTally sunlight;        // the visible share of the sun's disc

    void merge(const StageTicks& t) {
        trace += t.trace;
        sun += t.sun;
        ao += t.ao;
        emissive += t.emissive;
        shade += t.shade;
        atmosphere += t.atmosphere;
        primaryRays += t.primaryRays;
        occlusion.merge(t.occlusion);
        light.merge(t.light);
        sunlight.merge(t.sunlight);
    }
};

// The limits of each emitting body's rounds: the irradiance sums the bodies' independent
// estimates, so its variance is the sum of theirs, and each body aims at target / sqrt(bodies).
RoundLimits lightRounds(const Settings& settings, std::size_t bodies) {
    return roundLimits(settings.emissiveError / std::sqrt(double(std::max<std::size_t>(bodies, 1))),
                       settings.emissiveSamples);
}

// Seeds of a hit sample's progressive rounds, one stream per kind of secondary ray, so that
// the occlusion, the emitters and the sun of one pixel do not share their jitter.
enum class Stream : std::uint64_t { Occlusion = 0, Sun = 1, Emitters = 2 };
std::uint64_t streamSeed(std::uint64_t index, Stream stream) {
    return index * 4u + static_cast<std::uint64_t>(stream);
}

double luminance(const glm::dvec3& c) {
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

// The pixels of one block, in rows, and the ray through the centre of the full block.
struct Block {
    int n = 0;          // pixels (fewer than N where a tile's edge cuts the block)
    int rowLength = 0;  // pixels per row
    int px[N], py[N];
    core::Ray central;
};

// One sample's camera rays through the pixels of a block.
struct SampleRays {
    core::Ray rays[N];
    double tnear[N], tfar[N];  // the near and far planes along each ray
    double cosAxis[N];         // of the angle to the view axis: eye depth = t cosAxis
    double jx[N], jy[N];       // the sample's position in its pixel, [0, 1)^2
};

// A frame's loop: tiles (in parallel) -> pixel blocks -> samples -> pixels, written into the
// frame's AOV and display images. Every pixel is computed on its own, so the images do not
// depend on which thread traces which tile.
class FrameTrace {
  public:
    FrameTrace(const SurfaceTracer& tracer, const core::Camera& camera,
               const core::RenderInput& input, const Settings& settings, core::Frame& frame)
        : mTracer(tracer),
          mCamera(camera),
          mInput(input),
          mSettings(settings),
          mAov(frame.image),
          mDisplay(frame.display),
          mChannels(frame.image),
          mTilesX((camera.width() + settings.tileSize - 1) / settings.tileSize),
          mTilesY((camera.height() + settings.tileSize - 1) / settings.tileSize),
          mGrid(static_cast<int>(std::ceil(std::sqrt(double(settings.spp))))),
          mExposure(static_cast<float>(input.scene.camera.exposure)),
          mSunDirections(sunDirections(-input.scene.light.direction,
                                       input.scene.light.angularRadiusDeg, settings.sunSamples)),
          mAoRadius(input.scene.light.aoRadius),
          mAoSide(aoSide(settings)),
          mEmitters(input.scene.light.emissiveLight
                        ? core::emittingBodies(input.particles, input.materials)
                        : std::vector<core::EmittingBody>{}),
          mEmissiveSide(emissiveSide(settings)),
          mAoRounds(roundLimits(settings.aoError, settings.aoSamples)),
          mLightRounds(lightRounds(settings, mEmitters.size())),
          mSunRounds(roundLimits(settings.sunError, settings.sunSamples)),
          mSunDisc(input.scene.light.angularRadiusDeg > 0.0
                       ? std::optional<SunDisc>(std::in_place, -input.scene.light.direction,
                                                input.scene.light.angularRadiusDeg)
                       : std::nullopt),
          mAtmosphere(core::sceneAtmosphere(input.scene, input.particles, settings.surfaceLevel)),
          mSun(core::atmosphereSun(input.scene.light)) {}

    bool hasAtmosphere() const { return mAtmosphere.has_value(); }

    // Whether the sun has a disc whose shadow rays the stage "sun" times.
    bool sunDisc() const { return mSettings.shadows && mSunDirections.size() > 1; }

    std::size_t emitterCount() const { return mEmitters.size(); }

    int tileColumns() const { return mTilesX; }
    int tileRows() const { return mTilesY; }

    // Tile `index` of the tiles in rows, tileSize pixels a side; its blocks are cut at the
    // tile's edge (a tile may be smaller than a block).
    void traceTile(int index, Workspace& w, StageTicks& ticks) const {
        const int tile = mSettings.tileSize;
        const int x0 = (index % mTilesX) * tile, y0 = (index / mTilesX) * tile;
        const int x1 = std::min(x0 + tile, mCamera.width());
        const int y1 = std::min(y0 + tile, mCamera.height());
        for (int by = y0; by < y1; by += B)
            for (int bx = x0; bx < x1; bx += B)
                traceBlock(block(bx, by, std::min(bx + B, x1), std::min(by + B, y1)), w, ticks);
    }

    // Every sample of a block's pixels, then the pixels.
    void traceBlock(const Block& b, Workspace& w, StageTicks& ticks) const {
        PixelSamples pixels[N];
        // Where no ray of the block can meet a surface, its pixels keep the background (unless
        // they see an atmosphere).
        if (mAtmosphere || mTracer.blockMayHit(b.central))
            for (int k = 0; k < mSettings.spp; ++k) traceSample(b, k, pixels, w, ticks);
        // A part's images hold its rows alone (core/frame_part.h).
        for (int i = 0; i < b.n; ++i)
            writePixel(pixels[i], mSettings.spp, mExposure, b.px[i],
                       mInput.part.imageRow(b.py[i], mSettings.tileSize), mChannels, mAov,
                       mDisplay);
    }

    // Sample k of every pixel of a block: the camera rays, their shadow rays, the shading.
    void traceSample(const Block& b, int k, PixelSamples* pixels, Workspace& w,
                     StageTicks& ticks) const {
        const SampleRays r = sampleRays(b, k);
        SurfaceHit hits[N];
        bool found[N];
        float vis[N], open[N];
        glm::vec3 light[N];
        const auto t0 = Clock::now();
        mTracer.tracePrimary(b.n, b.rowLength, r.rays, r.tnear, r.tfar, b.central, hits, found, w);
        ticks.primaryRays += b.n;
        const auto tSun = Clock::now();
        if (mSettings.shadows)
            traceVisibility(b, k, hits, found, vis, w, ticks);
        else
            std::fill_n(vis, b.n, 1.0f);
        const auto tAo = Clock::now();
        ticks.trace += (tSun - t0).count();
        (sunDisc() ? ticks.sun : ticks.trace) += (tAo - tSun).count();
        std::fill_n(open, b.n, 1.0f);
        if (mAoRadius > 0.0) traceOcclusion(b, k, hits, found, open, w, ticks);
        const auto tLight = Clock::now();
        ticks.ao += (tLight - tAo).count();
        std::fill_n(light, b.n, glm::vec3(0.0f));
        if (!mEmitters.empty()) traceEmitters(b, k, hits, found, light, w, ticks);
        const auto tAir = Clock::now();
        ticks.emissive += (tAir - tLight).count();
        core::AtmosphereSample air[N];
        if (mAtmosphere) traceAtmosphere(b, r, hits, found, air);
        const auto t1 = Clock::now();
        ticks.atmosphere += (t1 - tAir).count();
        for (int i = 0; i < b.n; ++i) {
            if (!found[i]) {
                if (mAtmosphere) pixels[i].addSky(air[i].inscatter);
                continue;
            }
            ShadedSample s = shadeHit(hits[i], r.rays[i].direction, vis[i], mInput.materials,
                                      mInput.scene.light, open[i], light[i]);
            if (mAtmosphere) {
                s.beauty = s.beauty * air[i].transmittance + air[i].inscatter;
                pixels[i].inscatter += glm::dvec3(air[i].inscatter);
            }
            pixels[i].add(s, vis[i], hits[i], hits[i].t * r.cosAxis[i], r.jx[i], r.jy[i], open[i],
                          light[i]);
        }
        ticks.shade += (Clock::now() - t1).count();
    }

  private:
    // The atmosphere along each camera ray up to its end point: the exact hit, or the shell's
    // exit where the ray meets no surface.
    void traceAtmosphere(const Block& b, const SampleRays& r, const SurfaceHit* hits,
                         const bool* found, core::AtmosphereSample* air) const {
        for (int i = 0; i < b.n; ++i) {
            const glm::vec3 origin(r.rays[i].origin - mAtmosphere->centre);
            const float end = found[i] ? static_cast<float>(hits[i].t) : INFINITY;
            air[i] = core::integrateAtmosphere(*mAtmosphere, mSun, origin,
                                               glm::vec3(r.rays[i].direction), end);
        }
    }

    // The index of sample k of pixel i of a block among all the frame's samples: the seed of
    // its jitter, so that no value depends on the thread.
    std::uint64_t sampleIndex(const Block& b, int i, int k) const {
        const std::uint64_t pixel =
            std::uint64_t(b.py[i]) * std::uint64_t(mCamera.width()) + std::uint64_t(b.px[i]);
        return pixel * std::uint64_t(mSettings.spp) + std::uint64_t(k);
    }

    // The open fraction of each hit's hemisphere within light.ao_radius: aoSamples
    // cosine-weighted directions, stratified and jittered by the pixel and the sample, so
    // that the value does not depend on the thread; with raymarch.ao_error, in rounds.
    void traceOcclusion(const Block& b, int k, const SurfaceHit* hits, const bool* found,
                        float* open, Workspace& w, StageTicks& ticks) const {
        const int samples = mAoSide * mAoSide;
        for (int i = 0; i < b.n; ++i) {
            if (!found[i]) continue;
            if (mSettings.aoError > 0.0) {
                open[i] = occlusionInRounds(hits[i], sampleIndex(b, i, k), w, ticks.occlusion);
                continue;
            }
            const std::vector<glm::dvec3> directions =
                aoDirections(glm::dvec3(hits[i].normal), mAoSide, sampleIndex(b, i, k));
            open[i] = mTracer.traceOpen(hits[i], directions.data(), samples, mAoRadius, w);
            ticks.occlusion.add(aoStandardError(open[i], samples), samples);
        }
    }

    // One hit's open fraction from rounds of cosine-weighted directions until its standard
    // error is below raymarch.ao_error (raymarch/progressive_strata.h).
    float occlusionInRounds(const SurfaceHit& hit, std::uint64_t index, Workspace& w,
                            EstimateTally& tally) const {
        const glm::dvec3 normal(hit.normal);
        glm::dvec3 u, v;
        orthonormalBasis(normal, u, v);
        ProgressiveStrata strata(streamSeed(index, Stream::Occlusion));
        std::vector<glm::dvec3> directions;
        sampleInRounds(strata, mAoRounds, [&](const std::vector<glm::dvec2>& points, double* y) {
            directions.clear();
            for (const glm::dvec2& st : points)
                directions.push_back(hemisphereDirection(normal, u, v, st));
            const auto isOpen = std::make_unique<bool[]>(points.size());
            mTracer.traceOpen(hit, directions.data(), int(points.size()), mAoRadius, w,
                              isOpen.get());
            for (std::size_t j = 0; j < points.size(); ++j) y[j] = isOpen[j] ? 1.0 : 0.0;
        });
        tally.add(strata.standardError(), strata.points());
        tally.atCap += stoppedAtCap(strata, mAoRounds);
        return static_cast<float>(strata.mean());
    }

    // The irradiance at each hit from the emitting bodies: per body, emissiveSamples rays over
    // the cone its bounding sphere subtends (raymarch/emitter_cone.h), each taking the emitted
    // radiance where it first meets the surface if that is the body's own (an occluder, or
    // another emitter, whose light its own cone counts, gives 0). Stratified and jittered by the
    // pixel, the sample and the body, so that the value does not depend on the thread. The
    // standard error of the luminance is summed over the bodies' variances.
    // With raymarch.emissive_error, each body's estimate is taken in rounds instead.
    void traceEmitters(const Block& b, int k, const SurfaceHit* hits, const bool* found,
                       glm::vec3* light, Workspace& w, StageTicks& ticks) const {
        const int count = mEmissiveSide * mEmissiveSide;
        for (int i = 0; i < b.n; ++i) {
            if (!found[i]) continue;
            const glm::dvec3 normal(hits[i].normal);
            glm::dvec3 sum(0.0);
            double variance = 0.0;
            std::int64_t rays = 0;
            for (std::size_t e = 0; e < mEmitters.size(); ++e) {
                const core::EmittingBody& emitter = mEmitters[e];
                const std::uint64_t seed = sampleIndex(b, i, k) * mEmitters.size() + e;
                if (mSettings.emissiveError > 0.0) {
                    const double se =
                        emitterInRounds(hits[i], emitter, seed, sum, rays, w, ticks.light);
                    variance += se * se;
                    continue;
                }
                double y = 0.0, yy = 0.0;  // of count x weight x luminance, for the variance
                std::vector<EmitterSample> samples = emitterSamples(
                    hits[i].outside, normal, emitter.centre, emitter.radius, mEmissiveSide, seed);
                std::erase_if(samples, [](const EmitterSample& s) { return !(s.weight > 0.0); });
                std::vector<glm::dvec3> directions;
                for (const EmitterSample& s : samples) directions.push_back(s.direction);
                const std::vector<glm::dvec3> radiances =
                    emittedAlong(hits[i], directions, emitter, w);
                for (std::size_t j = 0; j < samples.size(); ++j) {
                    const EmitterSample& s = samples[j];
                    ++rays;
                    const glm::dvec3& radiance = radiances[j];
                    if (radiance == glm::dvec3(0.0)) continue;
                    sum += s.weight * radiance;
                    const double x = count * s.weight * luminance(radiance);
                    y += x;
                    yy += x * x;
                }
                if (count > 1)
                    variance += std::max(0.0, yy - y * y / count) / (double(count) * (count - 1));
            }
            light[i] = glm::vec3(sum);
            ticks.light.add(std::sqrt(variance), rays);
        }
    }

    // The radiance each ray from `from` along `directions` meets, if it meets `emitter` first;
    // 0 otherwise. Their crossings with the emitter lie within its bounding sphere: the
    // tracer gathers once for their way there.
    std::vector<glm::dvec3> emittedAlong(const SurfaceHit& from,
                                         const std::vector<glm::dvec3>& directions,
                                         const core::EmittingBody& emitter, Workspace& w) const {
        const std::size_t n = directions.size();
        std::vector<SurfaceHit> at(n);
        const auto found = std::make_unique<bool[]>(n);
        // The cone of the emitter's bounding sphere (emitter_cone.h), or the hemisphere inside it.
        const glm::dvec3 toCentre = emitter.centre - from.outside;
        const double distance = glm::length(toCentre);
        const double reach = distance + emitter.radius;
        const bool inside = !(distance > emitter.radius);
        const double sinHalf = inside ? 1.0 : emitter.radius / distance;
        mTracer.traceFirst(
            from, directions.data(), int(n), inside ? glm::dvec3(from.normal) : toCentre / distance,
            std::sqrt(std::max(0.0, 1.0 - sinHalf * sinHalf)), reach, at.data(), found.get(), w);
        std::vector<glm::dvec3> radiance(n, glm::dvec3(0.0));
        for (std::size_t j = 0; j < n; ++j)
            if (found[j] && at[j].body == emitter.body)
                radiance[j] = glm::dvec3(
                    core::surfaceEmission(mInput.materials[at[j].material], at[j].uv, at[j].glow));
        return radiance;
    }

    // One body's irradiance at a hit from rounds over its cone (raymarch/emitter_cone.h) until
    // the standard error of its luminance is below its share of raymarch.emissive_error: adds
    // the irradiance to `sum` and the rays traced to `rays`, returns the standard error.
    double emitterInRounds(const SurfaceHit& hit, const core::EmittingBody& emitter,
                           std::uint64_t seed, glm::dvec3& sum, std::int64_t& rays, Workspace& w,
                           EstimateTally& tally) const {
        const EmitterCone cone(hit.outside, glm::dvec3(hit.normal), emitter.centre, emitter.radius);
        ProgressiveStrata strata(streamSeed(seed, Stream::Emitters));
        glm::dvec3 weighted(0.0);  // of weight x radiance over every point
        std::vector<glm::dvec3> directions;
        std::vector<std::size_t> traced;  // the points whose direction has a weight
        sampleInRounds(strata, mLightRounds, [&](const std::vector<glm::dvec2>& points, double* y) {
            directions.clear();
            traced.clear();
            for (std::size_t j = 0; j < points.size(); ++j) {
                const glm::dvec3 direction = cone.direction(points[j]);
                y[j] = 0.0;
                if (!(cone.weight(direction) > 0.0)) continue;
                directions.push_back(direction);
                traced.push_back(j);
            }
            const std::vector<glm::dvec3> radiances = emittedAlong(hit, directions, emitter, w);
            for (std::size_t k = 0; k < traced.size(); ++k) {
                const double weight = cone.weight(directions[k]);
                ++rays;
                weighted += weight * radiances[k];
                y[traced[k]] = weight * luminance(radiances[k]);
            }
        });
        sum += weighted / double(strata.points());
        tally.atCap += stoppedAtCap(strata, mLightRounds);
        return strata.standardError();
    }

    // The sun's visibility from each hit: one bundle of parallel shadow rays per sun
    // direction, averaged (each direction's own n.l test included, so a point where part of
    // the disc has set sees that part occluded). With raymarch.sun_error, rounds per hit.
    void traceVisibility(const Block& b, int k, const SurfaceHit* hits, const bool* found,
                         float* vis, Workspace& w, StageTicks& ticks) const {
        const int n = b.n;
        if (mSunDirections.size() == 1) {
            mTracer.traceShadows(n, hits, found, mSunDirections[0], vis, w);
            return;
        }
        if (mSettings.sunError > 0.0) {
            sunInRounds(b, k, hits, found, vis, w, ticks.sunlight);
            return;
        }
        float one[N];
        double sum[N] = {};
        std::int64_t rays[N] = {};
        for (const glm::dvec3& toLight : mSunDirections) {
            mTracer.traceShadows(n, hits, found, toLight, one, w);
            for (int i = 0; i < n; ++i) {
                sum[i] += one[i];
                // traceShadows traces no ray where the light is below the horizon.
                rays[i] += glm::dot(glm::dvec3(hits[i].normal), toLight) > 0.0;
            }
        }
        const int count = static_cast<int>(mSunDirections.size());
        for (int i = 0; i < n; ++i) {
            vis[i] = static_cast<float>(sum[i] / count);
            // The spiral is fixed, not random: the binomial value of as many independent
            // directions stands for its error, as aoStandardError does for the occlusion.
            if (found[i]) ticks.sunlight.add(aoStandardError(sum[i] / count, count), rays[i]);
        }
    }

    // Each hit's visible share of the sun's disc from rounds of directions uniform over it,
    // until its standard error is below raymarch.sun_error. Every pixel takes the same
    // progressive pattern (seeded by the sample, not the pixel), as every pixel takes the same
    // spiral without a target: a round's new directions are then the block's, and their shadow
    // rays stay the parallel bundles of traceShadows, for the pixels still taking rounds.
    void sunInRounds(const Block& b, int k, const SurfaceHit* hits, const bool* found, float* vis,
                     Workspace& w, EstimateTally& tally) const {
        const int n = b.n;
        std::vector<ProgressiveStrata> strata(n, ProgressiveStrata(streamSeed(k, Stream::Sun)));
        bool active[N];
        std::int64_t rays[N] = {};
        std::copy_n(found, n, active);
        std::vector<double> y;
        float one[N];
        while (std::any_of(active, active + n, [](bool a) { return a; })) {
            const std::vector<glm::dvec2>* points = nullptr;
            for (int i = 0; i < n; ++i)
                if (active[i]) points = &strata[i].refine();  // the same points for every pixel
            const std::size_t m = points->size();
            y.assign(std::size_t(n) * m, 0.0);
            for (std::size_t j = 0; j < m; ++j) {
                const glm::dvec3 toLight = mSunDisc->direction((*points)[j]);
                mTracer.traceShadows(n, hits, active, toLight, one, w);
                for (int i = 0; i < n; ++i) {
                    if (!active[i]) continue;
                    y[std::size_t(i) * m + j] = one[i];
                    // traceShadows traces no ray where the light is below the horizon.
                    rays[i] += glm::dot(glm::dvec3(hits[i].normal), toLight) > 0.0;
                }
            }
            for (int i = 0; i < n; ++i) {
                if (!active[i]) continue;
                strata[i].record(&y[std::size_t(i) * m]);
                active[i] = !roundsDone(strata[i], mSunRounds);
            }
        }
        for (int i = 0; i < n; ++i) {
            vis[i] = 0.0f;
            if (!found[i]) continue;
            vis[i] = static_cast<float>(strata[i].mean());
            tally.add(strata[i].standardError(), rays[i]);
            tally.atCap += stoppedAtCap(strata[i], mSunRounds);
        }
    }

    // The pixels [x0, x1) x [y0, y1) of the block whose corner is (x0, y0).
    Block block(int x0, int y0, int x1, int y1) const {
        Block b;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                b.px[b.n] = x;
                b.py[b.n] = y;
                ++b.n;
            }
        b.rowLength = x1 - x0;
        b.central = mCamera.ray(x0 + 0.5 * B, y0 + 0.5 * B);
        return b;
    }

    // With one sample per pixel, the pixel centre; else stratified on a grid x grid pattern
    // and jittered.
    SampleRays sampleRays(const Block& b, int k) const {
        SampleRays r;
        const double nearT = mInput.scene.camera.near, farT = mInput.scene.camera.far;
        for (int i = 0; i < b.n; ++i) {
            r.jx[i] = r.jy[i] = 0.5;
            if (mSettings.spp > 1) {
                r.jx[i] = ((k % mGrid) + hashToUnit(b.px[i], b.py[i], k, 0)) / mGrid;
                r.jy[i] = ((k / mGrid) + hashToUnit(b.px[i], b.py[i], k, 1)) / mGrid;
            }
            r.rays[i] = mCamera.ray(b.px[i] + r.jx[i], b.py[i] + r.jy[i]);
            r.cosAxis[i] = glm::dot(r.rays[i].direction, mCamera.forward());
            r.tnear[i] = nearT / r.cosAxis[i];
            r.tfar[i] = farT / r.cosAxis[i];
        }
        return r;
    }

    const SurfaceTracer& mTracer;
    const core::Camera& mCamera;
    const core::RenderInput& mInput;
    const Settings& mSettings;
    core::Image& mAov;
    core::Image& mDisplay;
    AovChannels mChannels;
    int mTilesX, mTilesY;
    int mGrid;  // strata per side of a pixel's samples
    float mExposure;
    std::vector<glm::dvec3> mSunDirections;           // towards the light; one for a point sun
    double mAoRadius;                                 // light.ao_radius; 0: no occlusion rays
    int mAoSide;                                      // the occlusion pattern's side
    std::vector<core::EmittingBody> mEmitters;        // light.emissive_light: the emitting bodies
    int mEmissiveSide;                                // the emitters' pattern's side
    RoundLimits mAoRounds, mLightRounds, mSunRounds;  // with raymarch.*_error > 0
    std::optional<SunDisc> mSunDisc;                  // light.angular_radius > 0
    std::optional<core::Atmosphere> mAtmosphere;      // a body's atmosphere, if the scene has one
    core::AtmosphereSun mSun;
};

// What tracing a frame's tiles (or one part's) adds up: the thread time and the secondary
// estimates' tallies per row of tiles held, in row order, and their sum in that order.
struct TracedTiles {
    StageTicks ticks;
    std::vector<StageTicks> rows;
};

// The tiles of `input.part` (every tile of a whole frame) in parallel on the caller's arena, on
// one workspace per thread.
TracedTiles traceTiles(const FrameTrace& trace, Workspaces& workspaces,
                       const core::RenderInput& input) {
    std::vector<int> held;  // the tiles traced, in tile order
    for (int row = 0; row < trace.tileRows(); ++row)
        if (input.part.holdsRow(row))
            for (int column = 0; column < trace.tileColumns(); ++column)
                held.push_back(row * trace.tileColumns() + column);
    const int tiles = static_cast<int>(held.size());
    std::atomic<int> done{0};
    // Each tile's own, summed in tile order after the loop (a sum of doubles in the order
    // threads finish would depend on the threads), row by row of tiles (so that parts holding
    // whole rows join to the same sums: core/part_join.h).
    std::vector<StageTicks> perTile(static_cast<std::size_t>(tiles));
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles, 1), [&](const tbb::blocked_range<int>& r) {
        // Embree wants flush-to-zero and denormals-are-zero on every thread that traces.
        _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
        _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
        Workspace& w = *workspaces.local();
        for (int t = r.begin(); t != r.end(); ++t) {
            // A tile takes milliseconds: a cancelled frame stops within one tile per thread
            // (TBB cancels the tiles not yet started and rethrows in the caller).
            core::throwIfCancelled(input.cancel);
            const std::size_t i = static_cast<std::size_t>(t);
            trace.traceTile(held[i], w, perTile[i]);
            const int finished = ++done;
            if (input.progress) input.progress(double(finished) / tiles);
        }
    });
    TracedTiles out;
    const std::size_t columns = static_cast<std::size_t>(trace.tileColumns());
    for (std::size_t start = 0; start < perTile.size(); start += columns) {
        StageTicks row;
        for (std::size_t t = start; t < start + columns; ++t) row.merge(perTile[t]);
        out.ticks.merge(row);
        out.rows.push_back(row);
    }
    return out;
}

// What joining a part's frame with the others needs (core/part_join.h): each secondary
// estimate's mean standard error as the rows' sums and the hit samples, its largest error
// joined by the largest; every other counter is a sum over the tiles but the count of emitting
// bodies, a fact of the whole frame.
core::PartRecord partRecord(const core::FramePart& part, int tileSize, int height,
                            const TracedTiles& traced,
                            const std::map<std::string, double>& counters) {
    core::PartRecord r;
    r.part = part;
    r.tileSize = tileSize;
    r.height = height;
    const auto mean = [&](const std::string& prefix, EstimateTally StageTicks::*tally) {
        if (!counters.count(prefix + "_standard_error")) return;
        core::PartMean& m = r.means[prefix + "_standard_error"];
        for (const StageTicks& row : traced.rows) m.rowSums.push_back((row.*tally).errorSum);
        m.samples = (traced.ticks.*tally).estimates;
        r.maxima.push_back(prefix + "_standard_error_max");
    };
    mean("ao", &StageTicks::occlusion);
    mean("irradiance", &StageTicks::light);
    mean("sun", &StageTicks::sunlight);
    if (counters.count("emitting_bodies")) r.shared = {"emitting_bodies"};
    return r;
}

// The counters of every thread's workspace, summed.
void collectCounters(const SurfaceTracer& tracer, const Workspaces& workspaces,
                     std::map<std::string, double>& counters) {
    TraceCounters total;
    for (const auto& w : workspaces) {
        const TraceCounters& c = tracer.counters(*w);
        total.unresolved += c.unresolved;
        total.candidates += c.candidates;
        total.evaluations += c.evaluations;
        total.segments += c.segments;
        total.bundles += c.bundles;
    }
    counters["unbracketed_rays"] = double(total.unresolved);
    counters["segments"] = double(total.segments);
    counters["candidates"] = double(total.candidates);
    counters["field_evaluations"] = double(total.evaluations);
    counters["bundle_gathers"] = double(total.bundles);
}

}  // namespace

Renderer::Renderer(const EmbreeDevice& device, const Settings& settings)
    : mDevice(device), mSettings(settings) {}

core::Frame Renderer::render(const core::RenderInput& input) {
    core::throwIfCancelled(input.cancel);
    const core::Camera camera(input.scene.camera);
    const bool occlusion = input.scene.light.aoRadius > 0.0;
    const bool emissive = input.scene.light.emissiveLight;
    const SurfaceTracer tracer(mDevice, camera, input.particles, mSettings,
                               occlusion || emissive);  // "build"
    core::Frame frame;
    frame.renderer = "raymarch";
    // The background values of core::aov::makeImage (Z = +inf, id = -1, the rest 0) are
    // written by the tiles, in parallel, with the pixels they cover: filling the channels
    // first is a serial pass over the whole image.
    const int height = input.part.heightHeld(camera.height(), mSettings.tileSize);
    frame.image = core::Image(camera.width(), height, core::aov::channelNames());
    frame.display = core::Image(camera.width(), height, {"R", "G", "B"});
    frame.particleCount = input.particles.particles.size();

    const FrameTrace trace(tracer, camera, input, mSettings, frame);
    Workspaces workspaces([&] { return tracer.makeWorkspace(); });
    const auto start = Clock::now();
    const TracedTiles traced = traceTiles(trace, workspaces, input);
    const StageTicks& ticks = traced.ticks;
    const double traceMs = msSince(start);
    // Split the parallel wall time by the thread time of each part.
    const double sum =
        std::max(double(ticks.trace) + double(ticks.sun) + double(ticks.ao) +
                     double(ticks.emissive) + double(ticks.shade) + double(ticks.atmosphere),
                 1.0);
    frame.timingsMs["build"] = tracer.buildMs();
    frame.timingsMs["trace"] = traceMs * double(ticks.trace) / sum;  // surfaces, shadow rays
    if (trace.sunDisc()) frame.timingsMs["sun"] = traceMs * double(ticks.sun) / sum;
    frame.timingsMs["ao"] = traceMs * double(ticks.ao) / sum;
    if (emissive) frame.timingsMs["emissive"] = traceMs * double(ticks.emissive) / sum;
    if (trace.hasAtmosphere())
        frame.timingsMs["atmosphere"] = traceMs * double(ticks.atmosphere) / sum;
    frame.timingsMs["shade"] = traceMs * double(ticks.shade) / sum;
    frame.timingsMs["total"] = tracer.buildMs() + traceMs;

    collectCounters(tracer, workspaces, frame.counters);
    frame.counters["primary_rays"] = double(ticks.primaryRays);
    // Per kind of secondary ray, the mean over the hit samples of each one's standard error
    // (what the reference's own noise adds to a per-pixel error: ao.mean_abs, indirect.rmse),
    // the largest, and the rays traced.
    if (occlusion) ticks.occlusion.write("ao", mSettings.aoError > 0.0, frame.counters);
    if (emissive) {
        // In luminance, the unit of the irradiance channels.
        ticks.light.write("irradiance", mSettings.emissiveError > 0.0, frame.counters);
        frame.counters["emitting_bodies"] = double(trace.emitterCount());
    }
    if (trace.sunDisc()) ticks.sunlight.write("sun", mSettings.sunError > 0.0, frame.counters);
    frame.device =
        fmt::format("{} ({} threads)", cpuName(), tbb::this_task_arena::max_concurrency());
    frame.settings = toJson(mSettings);
    if (!input.part.whole())
        frame.part =
            partRecord(input.part, mSettings.tileSize, camera.height(), traced, frame.counters);
    return frame;
}

}  // namespace twinrender::raymarch
