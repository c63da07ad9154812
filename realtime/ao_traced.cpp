#include "realtime/ao_traced.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "realtime/passes.h"

namespace twinrender::realtime {

namespace {

// The grid's storage bindings (shaders/ao_traced.frag). The per-set compute passes, which use
// them too, bind their own buffers before each dispatch.
constexpr unsigned CELL_START_BINDING = 5, ITEMS_BINDING = 6, SPHERES_BINDING = 7;

// Calls f(i) for each index of `indices`, or for 0..n-1 when it is empty.
template <typename F>
void forEachIndex(std::size_t n, std::span<const std::uint32_t> indices, F&& f) {
    if (indices.empty())
        for (std::size_t i = 0; i < n; ++i) f(static_cast<std::uint32_t>(i));
    else
        for (const std::uint32_t i : indices) f(i);
}

}  // namespace

OcclusionGrid buildOcclusionGrid(const core::ParticleSet& particles, std::span<const float> radii,
                                 std::span<const std::uint32_t> indices, const glm::dvec3& camera,
                                 double reach) {
    OcclusionGrid g;
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    double largest = 0.0;
    forEachIndex(particles.size(), indices, [&](std::uint32_t i) {
        const double r = radii[i];
        if (!(r > 0.0)) return;
        const glm::dvec3 c = glm::dvec3(particles.position[i]) - camera;
        g.spheres.emplace_back(glm::vec3(c), static_cast<float>(r));
        lo = glm::min(lo, c - r);
        hi = glm::max(hi, c + r);
        largest = std::max(largest, r);
    });
    if (g.spheres.empty()) return g;  // one empty cell
    const glm::dvec3 extent = glm::max(hi - lo, glm::dvec3(1e-9));
    const double maxCells = std::max(8.0 * static_cast<double>(g.spheres.size()), 4096.0);
    double side = std::max(largest, reach / 64.0);
    const auto cellsAt = [&](double s) { return glm::max(glm::ceil(extent / s), glm::dvec3(1.0)); };
    while (true) {
        const glm::dvec3 n = cellsAt(side);
        if (n.x * n.y * n.z <= maxCells) break;
        side *= 1.25;
    }
    g.cells = glm::ivec3(cellsAt(side));
    g.origin = glm::vec3(lo);
    g.side = static_cast<float>(side);

    // The cells each sphere's box overlaps, widened by a little against the shader's float
    // rounding at a cell's face.
    const double pad = 1e-5 * side;
    const auto range = [&](const glm::vec4& s, glm::ivec3& first, glm::ivec3& last) {
        const glm::dvec3 c(s.x, s.y, s.z);
        const double r = s.w + pad;
        first = glm::clamp(glm::ivec3(glm::floor((c - r - lo) / side)), glm::ivec3(0), g.cells - 1);
        last = glm::clamp(glm::ivec3(glm::floor((c + r - lo) / side)), glm::ivec3(0), g.cells - 1);
    };
    const auto forEachCell = [&](const glm::vec4& s, auto&& f) {
        glm::ivec3 first, last;
        range(s, first, last);
        for (int z = first.z; z <= last.z; ++z)
            for (int y = first.y; y <= last.y; ++y)
                for (int x = first.x; x <= last.x; ++x)
                    f(static_cast<std::size_t>(x) +
                      static_cast<std::size_t>(g.cells.x) *
                          (static_cast<std::size_t>(y) + static_cast<std::size_t>(g.cells.y) * z));
    };
    // Counting sort: the counts, their prefix sum, then each sphere placed in order.
    const std::size_t cellCount = static_cast<std::size_t>(g.cells.x) * g.cells.y * g.cells.z;
    g.cellStart.assign(cellCount + 1, 0u);
    for (const glm::vec4& s : g.spheres)
        forEachCell(s, [&](std::size_t c) { ++g.cellStart[c + 1]; });
    for (std::size_t c = 0; c < cellCount; ++c) g.cellStart[c + 1] += g.cellStart[c];
    g.items.resize(g.cellStart[cellCount]);
    std::vector<std::uint32_t> next(g.cellStart.begin(), g.cellStart.end() - 1);
    for (std::size_t k = 0; k < g.spheres.size(); ++k)
        forEachCell(g.spheres[k], [&](std::size_t c) { g.items[next[c]++] = k; });
    return g;
}

OcclusionGrid OcclusionGridCache::grid(const core::SceneParticles& particles,
                                       const ParticleSettings& settings, const glm::dvec3& camera,
                                       double reach) {
    const core::ParticleSet& ps = mNormals.particles(particles);
    const std::vector<float>& radii = mRadii.radii(ps, settings);
    // The culling is exact for spheres whatever the particles' drawn shape; it is kept per set.
    std::span<const std::uint32_t> shown;
    if (settings.cullHidden) shown = mCuller.unoccluded(ps, radii);
    return buildOcclusionGrid(ps, radii, shown, camera, reach);
}

OcclusionGridBuffers uploadOcclusionGrid(const OcclusionGrid& grid) {
    OcclusionGridBuffers out;
    out.cellStart = gl::Buffer::of(std::span<const std::uint32_t>(grid.cellStart));
    out.items = gl::Buffer::of(std::span<const std::uint32_t>(grid.items));
    out.spheres = gl::Buffer::of(std::span<const glm::vec4>(grid.spheres));
    out.originSide = glm::vec4(grid.origin, grid.side);
    out.cells = glm::vec3(grid.cells);
    return out;
}

const gl::Program& tracedOcclusionProgram(ProgramCache& programs, const AoSettings& settings,
                                          const OcclusionGridBuffers& grid) {
    const gl::Program& program =
        programs.get("fullscreen.vert", "ao_traced.frag", ambientOcclusionDefines(settings));
    program.set("uRays", settings.rays);
    program.set("uBias", static_cast<float>(TRACED_ORIGIN_BIAS));
    program.set("uMaxLift", static_cast<float>(TRACED_MAX_LIFT));
    program.set("uGridOriginSide", grid.originSide);
    program.set("uGridCells", grid.cells);
    grid.cellStart.bindStorage(CELL_START_BINDING);
    grid.items.bindStorage(ITEMS_BINDING);
    grid.spheres.bindStorage(SPHERES_BINDING);
    return program;
}

}  // namespace twinrender::realtime
