#include "raymarch/renderer.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <mutex>
#include <pmmintrin.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>

#include "core/camera.h"
#include "core/shading.h"
#include "raymarch/surface_tracer.h"

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

}  // namespace

Renderer::Renderer(const EmbreeDevice& device, const Settings& settings)
    : mDevice(device), mSettings(settings) {}

core::Frame Renderer::render(const core::RenderInput& input) {
    const Settings& st = mSettings;
    const core::Camera camera(input.scene.camera);
    const SurfaceTracer tracer(mDevice, camera, input.particles, st);  // "build"
    const auto& progress = input.progress;
    const int width = camera.width(), height = camera.height();
    const int tile = st.tileSize;
    const int tilesX = (width + tile - 1) / tile, tilesY = (height + tile - 1) / tile;
    const int tileCount = tilesX * tilesY;
    core::Frame frame;
    frame.renderer = "raymarch";
    // The background values of core::aov::makeImage (Z = +inf, id = -1, the rest 0) are
    // written by the tiles, in parallel, with the pixels they cover: filling the channels
    // first is a serial pass over the whole image.
    frame.image = core::Image(width, height, core::aov::channelNames());
    frame.display = core::Image(width, height, {"R", "G", "B"});
    frame.particleCount = input.particles.particles.size();
    core::Image& img = frame.image;
    const float exposure = static_cast<float>(input.scene.camera.exposure);
    const int cR = img.channelIndex("R"), cA = img.channelIndex("A"), cZ = img.channelIndex("Z"),
              cN = img.channelIndex("N.X"), cU = img.channelIndex("uv.U"), cId = img.channelIndex("id"),
              cE = img.channelIndex("emission.R"), cS = img.channelIndex("shadow");
    const double nearT = input.scene.camera.near, farT = input.scene.camera.far;
    const glm::dvec3 toLight = -input.scene.light.direction;
    const int grid = static_cast<int>(std::ceil(std::sqrt(double(st.spp))));
    std::atomic<int> done{0};
    std::atomic<std::int64_t> primaryNs{0}, shadeNs{0};
    tbb::enumerable_thread_specific<SurfaceTracer::WorkspacePtr> workspaces(
        [&] { return tracer.makeWorkspace(); });
    const auto start = Clock::now();

    tbb::parallel_for(tbb::blocked_range<int>(0, tileCount, 1), [&](const tbb::blocked_range<int>& range) {
        // Embree wants flush-to-zero and denormals-are-zero on every thread that traces.
        _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
        _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
        SurfaceTracer::Workspace& w = *workspaces.local();
        constexpr int B = SurfaceTracer::BLOCK;
        constexpr int N = B * B;
        for (int ti = range.begin(); ti != range.end(); ++ti) {
            const int tx0 = (ti % tilesX) * tile, ty0 = (ti / tilesX) * tile;
            // Blocks are cut at the tile's edge (a tile may be smaller than a block).
            const int tx1 = std::min(tx0 + tile, width), ty1 = std::min(ty0 + tile, height);
            std::int64_t tPrimary = 0, tShade = 0;
            for (int by = ty0; by < ty1; by += B)
                for (int bx = tx0; bx < tx1; bx += B) {
                    int px[N], py[N], n = 0;
                    for (int y = by; y < std::min(by + B, ty1); ++y)
                        for (int x = bx; x < std::min(bx + B, tx1); ++x) {
                            px[n] = x;
                            py[n] = y;
                            ++n;
                            img.at(x, y, cZ) = std::numeric_limits<float>::infinity();
                            img.at(x, y, cId) = -1.0f;
                        }
                    // Per pixel of the block, summed over its samples (glm does not zero).
                    glm::dvec3 beauty[N], emission[N];
                    std::fill_n(beauty, N, glm::dvec3(0.0));
                    std::fill_n(emission, N, glm::dvec3(0.0));
                    double coverage[N] = {}, shadow[N] = {}, bestDist[N];
                    std::fill_n(bestDist, N, INFINITY);
                    const core::Ray central = camera.ray(bx + 0.5 * B, by + 0.5 * B);
                    // Background (written above) where no ray of the block can meet a surface.
                    if (!tracer.blockMayHit(central)) continue;
                    for (int k = 0; k < st.spp; ++k) {
                        core::Ray rays[N];
                        double tnear[N], tfar[N], cosAxis[N], jx[N], jy[N];
                        for (int i = 0; i < n; ++i) {
                            jx[i] = jy[i] = 0.5;
                            if (st.spp > 1) {
                                jx[i] = ((k % grid) + hashToUnit(px[i], py[i], k, 0)) / grid;
                                jy[i] = ((k / grid) + hashToUnit(px[i], py[i], k, 1)) / grid;
                            }
                            rays[i] = camera.ray(px[i] + jx[i], py[i] + jy[i]);
                            cosAxis[i] = glm::dot(rays[i].direction, camera.forward());
                            tnear[i] = nearT / cosAxis[i];
                            tfar[i] = farT / cosAxis[i];
                        }
                        SurfaceHit hits[N];
                        bool found[N];
                        float vis[N];
                        const auto t0 = Clock::now();
                        const int rowLength = std::min(bx + B, tx1) - bx;
                        tracer.tracePrimary(n, rowLength, rays, tnear, tfar, central, hits, found, w);
                        if (st.shadows) tracer.traceShadows(n, hits, found, toLight, vis, w);
                        else std::fill_n(vis, n, 1.0f);
                        const auto t1 = Clock::now();
                        tPrimary += (t1 - t0).count();
                        for (int i = 0; i < n; ++i) {
                            if (!found[i]) continue;
                            const SurfaceHit& hit = hits[i];
                            core::SurfacePoint sp;
                            sp.normal = hit.normal;
                            sp.toEye = glm::vec3(-rays[i].direction);
                            sp.uv = hit.uv;
                            sp.material = hit.material;
                            sp.emission = core::surfaceEmission(input.materials[hit.material], hit.uv, hit.glow);
                            sp.visibility = vis[i];
                            beauty[i] += glm::dvec3(core::shade(input.materials, input.scene.light, sp));
                            emission[i] += glm::dvec3(sp.emission);
                            coverage[i] += 1.0;
                            shadow[i] += vis[i];
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
                        tShade += (Clock::now() - t1).count();
                    }
                    for (int i = 0; i < n; ++i) {
                        if (coverage[i] == 0.0) continue;
                        const int x = px[i], y = py[i];
                        const double inv = 1.0 / st.spp;
                        glm::vec3 mean;
                        for (int c = 0; c < 3; ++c) {
                            mean[c] = static_cast<float>(beauty[i][c] * inv);
                            img.at(x, y, cR + c) = mean[c];
                            img.at(x, y, cE + c) = static_cast<float>(emission[i][c] / coverage[i]);
                        }
                        // The background's display value, tonemap(0), is 0: the new image's.
                        const glm::vec3 shown = core::tonemap(mean, exposure);
                        for (int c = 0; c < 3; ++c) frame.display.at(x, y, c) = shown[c];
                        img.at(x, y, cA) = static_cast<float>(coverage[i] * inv);
                        img.at(x, y, cS) = static_cast<float>(shadow[i] / coverage[i]);
                    }
                }
            primaryNs += tPrimary;
            shadeNs += tShade;
            const int finished = ++done;
            if (progress) progress(double(finished) / tileCount);
        }
    });
    const double traceMs = msSince(start);
    // Split the parallel wall time by the thread time of each part.
    const double primary = double(primaryNs.load()), shading = double(shadeNs.load());
    const double sum = std::max(primary + shading, 1.0);
    frame.timingsMs["build"] = tracer.buildMs();
    frame.timingsMs["trace"] = traceMs * primary / sum;  // surfaces and shadow rays
    frame.timingsMs["shade"] = traceMs * shading / sum;
    frame.timingsMs["total"] = tracer.buildMs() + traceMs;

    TraceCounters total;
    for (auto& w : workspaces) {
        const TraceCounters& c = tracer.counters(*w);
        total.unresolved += c.unresolved;
        total.candidates += c.candidates;
        total.evaluations += c.evaluations;
        total.segments += c.segments;
        total.bundles += c.bundles;
    }
    frame.counters["unbracketed_rays"] = double(total.unresolved);
    frame.counters["segments"] = double(total.segments);
    frame.counters["candidates"] = double(total.candidates);
    frame.counters["field_evaluations"] = double(total.evaluations);
    frame.counters["bundle_gathers"] = double(total.bundles);
    frame.device = fmt::format("{} ({} threads)", cpuName(), tbb::this_task_arena::max_concurrency());
    frame.settings = toJson(st);
    return frame;
}

}  // namespace twinrender::raymarch
