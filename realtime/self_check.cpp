#include "realtime/self_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <glm/common.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "core/derived_attributes.h"
#include "realtime/impostor_radius.h"
#include "realtime/occlusion_culling.h"
#include "realtime/per_set_gpu.h"

namespace twinrender::realtime {

bool SelfCheck::passed() const {
    return !checks.empty() &&
           std::all_of(checks.begin(), checks.end(), [](const Check& c) { return c.pass; });
}

std::string SelfCheck::table() const {
    std::string out;
    for (const Check& c : checks)
        out += fmt::format("  {:<44} cpu {:>10g}  gpu {:>10g}  bound {:>8g}  {}  ({})\n", c.name,
                           c.cpu, c.gpu, c.bound, c.pass ? "pass" : "FAIL", c.why);
    for (const std::string& note : notes) out += "    " + note + "\n";
    return out;
}

namespace {

double counter(const core::Frame& f, const char* name) {
    const auto it = f.counters.find(name);
    return it == f.counters.end() ? 0.0 : it->second;
}

// Pixels whose coverage or body differ, and covered pixels whose red differs by over 1e-2;
// and the covered pixels of the CPU's frame.
struct ImageDifference {
    int covered = 0, apart = 0, shadedApart = 0;
};
ImageDifference imageDifference(const core::Frame& cpu, const core::Frame& gpu) {
    ImageDifference d;
    const core::Image &c = cpu.image, &g = gpu.image;
    if (c.width() != g.width() || c.height() != g.height()) {
        d.apart = c.width() * c.height();
        return d;
    }
    const int alpha = c.requireChannel("A"), id = c.requireChannel("id"),
              red = c.requireChannel("R");
    for (int y = 0; y < c.height(); ++y)
        for (int x = 0; x < c.width(); ++x) {
            const bool covered = c.at(x, y, alpha) > 0.5f;
            d.covered += covered;
            if (c.at(x, y, alpha) != g.at(x, y, alpha) || c.at(x, y, id) != g.at(x, y, id)) {
                ++d.apart;
                continue;
            }
            // NaN on either side counts as apart.
            if (covered && !(std::abs(c.at(x, y, red) - g.at(x, y, red)) <= 1e-2f)) ++d.shadedApart;
        }
    return d;
}

}  // namespace

SelfCheck selfCheck(Device& device, const Settings& settings, const core::RenderInput& input) {
    core::Frame frames[2];
    for (const PerSetDevice where : {PerSetDevice::Cpu, PerSetDevice::Gpu}) {
        Settings s = settings;
        s.perSet = where;
        s.perSetFallback = false;  // each path as asked, whatever the device's verdict
        Renderer renderer(device, s);
        frames[where == PerSetDevice::Cpu ? 0 : 1] = renderer.render(input);
    }
    const core::Frame &cpu = frames[0], &gpu = frames[1];
    SelfCheck out;
    auto add = [&](std::string name, double c, double g, double bound, bool pass, std::string why) {
        out.checks.push_back({std::move(name), c, g, bound, pass, std::move(why)});
    };
    const double drawnCpu = counter(cpu, "particles_drawn"),
                 drawnGpu = counter(gpu, "particles_drawn");
    add("particles_drawn", drawnCpu, drawnGpu, 3.0, std::abs(drawnCpu - drawnGpu) <= 3.0,
        "within 3: radii agree within 3e-4 h");
    const double dropletsCpu = counter(cpu, "droplets"), dropletsGpu = counter(gpu, "droplets");
    add("droplets", dropletsCpu, dropletsGpu, 0.0, dropletsCpu == dropletsGpu, "equal");
    const double spheresCpu = counter(cpu, "body_spheres"),
                 spheresGpu = counter(gpu, "body_spheres");
    add("body_spheres", spheresCpu, spheresGpu, 0.0, spheresCpu == spheresGpu, "equal");
    const ImageDifference d = imageDifference(cpu, gpu);
    const double bound = std::max(d.covered / 200, 1);
    add("covered_pixels", d.covered, d.covered, 1.0, d.covered > 0, "something drawn");
    add("coverage_or_body_apart", 0.0, d.apart, bound, d.apart <= bound,
        "pixels, at most 1 in 200 covered");
    add("shading_apart", 0.0, d.shadedApart, bound, d.shadedApart <= bound,
        "covered pixels whose red differs over 1e-2, at most 1 in 200");
    return out;
}

namespace {

// shaders/per_set_stages.glsl's flag bits.
constexpr std::uint32_t HIDDEN = 2, INTERIOR = 4, SPARSE = 8;

// The CPU's answers for one set: radii, the spheres left visible, and those drawn.
struct CpuAnswers {
    std::vector<float> radii;
    std::vector<std::uint32_t> visible;
    double drawn = 0.0;
};
CpuAnswers cpuAnswers(const core::ParticleSet& ps, const PerSetRequest& request) {
    CpuAnswers a;
    a.radii = impostorRadii(ps, request.particles);
    if (request.cull) {
        a.visible = unoccludedParticles(ps, a.radii);
    } else {
        for (std::size_t i = 0; i < ps.size(); ++i) a.visible.push_back(std::uint32_t(i));
    }
    for (std::uint32_t i : a.visible) a.drawn += a.radii[i] > 0.0f;
    return a;
}

std::string vec3Text(const glm::vec3& v) {
    return fmt::format("({:g}, {:g}, {:g})", v.x, v.y, v.z);
}

// The first particle that is not in GATHER's order exactly once.
std::string firstMissing(const std::vector<int>& seen) {
    for (std::size_t i = 0; i < seen.size(); ++i)
        if (seen[i] != 1) return fmt::format("particle {} is in {} slots", i, seen[i]);
    return "a slot holds an index beyond the particles";
}

// The Attributes buffer (shaders/per_set.glsl) word `k` of a set of `n`: its attribute, its
// particle and component.
std::string attributeWordText(std::size_t k, std::size_t n) {
    struct Run {
        std::size_t offset;
        const char* name;
        std::size_t components;
    };
    static constexpr Run RUNS[] = {{0, "position", 3}, {3, "h", 1},     {4, "volume", 1},
                                   {5, "normal", 3},   {8, "body", 1},  {9, "uv", 2},
                                   {11, "dudx", 3},    {14, "dvdx", 3}, {17, "glow", 3},
                                   {20, "material", 1}};
    const Run* run = &RUNS[0];
    for (const Run& r : RUNS)
        if (r.offset * n <= k) run = &r;
    const std::size_t within = k - run->offset * n;
    return fmt::format("particle {}'s {}[{}]", within / run->components, run->name,
                       within % run->components);
}

// The upload: the Attributes buffer word for word against the CPU's layout of the set (where
// the set came with normals no stage writes it).
void checkUpload(const GpuPerSet& g, const core::ParticleSet& ps, const std::string& suffix,
                 SelfCheck& out) {
    const std::vector<std::uint32_t> gpu = g.attributes(), cpu = attributeWords(ps);
    double apart = 0.0;
    std::string first;
    for (std::size_t k = 0; k < cpu.size(); ++k) {
        const std::uint32_t seen = k < gpu.size() ? gpu[k] : 0u;
        if (seen == cpu[k]) continue;
        if (++apart == 1)
            first = fmt::format("{}: cpu {:g} gpu {:g} (word {:#010x})",
                                attributeWordText(k, ps.size()), std::bit_cast<float>(cpu[k]),
                                std::bit_cast<float>(seen), seen);
    }
    out.checks.push_back({"attribute_words_apart" + suffix, 0.0, apart, 0.0, apart == 0.0,
                          "the Attributes buffer after the upload, word for word", "upload",
                          first});
}

// What H_MIN, LEVELS and LAYOUT must leave for `ps` (shaders/per_set_grid.comp, in float as
// they compute it).
GpuPerSet::Levels cpuLevels(const core::ParticleSet& ps) {
    constexpr int MAX_LEVELS = 32;  // per_set_layout.h
    GpuPerSet::Levels out;
    out.hMin = std::numeric_limits<float>::infinity();
    for (const float h : ps.h) out.hMin = std::min(out.hMin, h);
    const float inf = std::numeric_limits<float>::infinity();
    out.levels.assign(MAX_LEVELS, {.low = glm::vec3(inf), .high = glm::vec3(-inf)});
    for (std::size_t i = 0; i < ps.size(); ++i) {
        const float ratio = std::max(ps.h[i] / out.hMin, 1.0f);
        const int level = std::clamp(
            static_cast<int>(std::bit_cast<std::uint32_t>(ratio) >> 23) - 127, 0, MAX_LEVELS - 1);
        GpuPerSet::Level& l = out.levels[static_cast<std::size_t>(level)];
        l.low = glm::min(l.low, ps.position[i]);
        l.high = glm::max(l.high, ps.position[i]);
        ++l.count;
        l.hMax = std::max(l.hMax, ps.h[i]);
    }
    int first = 0;
    for (GpuPerSet::Level& l : out.levels) {
        if (l.count == 0) {
            l.dims = glm::ivec4(1, 1, 1, first);
            continue;
        }
        const glm::vec3 extent = l.high - l.low;
        const float maxCells = std::max(4.0f * static_cast<float>(l.count), 4096.0f);
        float cell = l.hMax;
        glm::vec3 n(1.0f);
        for (int k = 0; k < 200; ++k) {
            n = glm::floor(extent / cell) + 1.0f;
            const float total = n.x * n.y * n.z;
            if (total <= maxCells) break;
            cell *= std::max(1.01f, std::pow(total / maxCells, 1.0f / 3.0f));
        }
        l.originCell = glm::vec4(l.low, cell);
        l.dims = glm::ivec4(glm::ivec3(n), first);
        first += static_cast<int>(n.x * n.y * n.z);
    }
    out.totalCells = static_cast<std::uint32_t>(first);
    return out;
}

std::string levelText(const GpuPerSet::Level& l) {
    return fmt::format("{} particles in {} - {}, largest h {:g}", l.count, vec3Text(l.low),
                       vec3Text(l.high), l.hMax);
}

// The levels (H_MIN, LEVELS: the least h, each level's box, count, largest h; exact) and their
// grids (LAYOUT: the corner exact, the cells along each axis within one, the cell count within
// the levels' surface cells that one more layer along each axis adds).
void checkLevels(const GpuPerSet& g, const core::ParticleSet& ps, const std::string& suffix,
                 SelfCheck& out) {
    const GpuPerSet::Levels gpu = g.levels(), cpu = cpuLevels(ps);
    double apart = gpu.hMin == cpu.hMin ? 0.0 : 1.0;
    std::string first = apart == 0.0
                            ? std::string()
                            : fmt::format("the least h: cpu {:g} gpu {:g}", cpu.hMin, gpu.hMin);
    double layoutApart = 0.0;
    std::string firstLayout;
    double cellSlack = 0.0;
    for (std::size_t L = 0; L < cpu.levels.size() && L < gpu.levels.size(); ++L) {
        const GpuPerSet::Level &c = cpu.levels[L], &q = gpu.levels[L];
        if (c.count == 0 && q.count == 0) continue;
        if (c.count != q.count || c.low != q.low || c.high != q.high || c.hMax != q.hMax) {
            if (++apart == 1)
                first = fmt::format("level {}: cpu {}; gpu {}", L, levelText(c), levelText(q));
            continue;
        }
        const glm::ivec3 d = glm::abs(glm::ivec3(c.dims) - glm::ivec3(q.dims));
        const bool sameLayout =
            glm::vec3(c.originCell) == glm::vec3(q.originCell) && d.x <= 1 && d.y <= 1 && d.z <= 1;
        cellSlack += (c.dims.x + 1.0) * (c.dims.y + 1.0) * (c.dims.z + 1.0) -
                     double(c.dims.x) * c.dims.y * c.dims.z;
        if (!sameLayout && ++layoutApart == 1)
            firstLayout = fmt::format(
                "level {}: cpu corner {} cells {} x {} x {}; gpu corner {} cells {} x {} x {}", L,
                vec3Text(glm::vec3(c.originCell)), c.dims.x, c.dims.y, c.dims.z,
                vec3Text(glm::vec3(q.originCell)), q.dims.x, q.dims.y, q.dims.z);
    }
    out.checks.push_back({"levels_apart" + suffix, 0.0, apart, 0.0, apart == 0.0,
                          "H_MIN and LEVELS: the least h, each level's box, count, largest h",
                          "levels", first});
    const double cells = std::abs(double(gpu.totalCells) - double(cpu.totalCells));
    if (layoutApart == 0.0 && cells > cellSlack)
        firstLayout =
            fmt::format("cells of all levels: cpu {} gpu {}", cpu.totalCells, gpu.totalCells);
    out.checks.push_back({"layout_apart" + suffix, double(cpu.totalCells), double(gpu.totalCells),
                          cellSlack, layoutApart == 0.0 && cells <= cellSlack,
                          "LAYOUT: corners exact, cells per axis within 1 of the CPU's float "
                          "mirror; the total within what that allows",
                          "layout", firstLayout});
}

// The grid's records (GpuPerSet::Grid) against what they must be for `ps`: the number of
// slots, cells or entries that break a rule.
void checkGrid(const GpuPerSet& g, const core::ParticleSet& ps, const std::string& suffix,
               SelfCheck& out) {
    const GpuPerSet::Grid grid = g.grid();
    const std::size_t n = ps.size();
    std::vector<int> seen(n, 0);
    double notPermutation = 0.0;
    for (std::uint32_t i : grid.sorted) {
        if (i < n)
            ++seen[i];
        else
            ++notPermutation;
    }
    for (int count : seen) notPermutation += count != 1;
    out.checks.push_back({"grid_slots_not_a_permutation" + suffix, 0.0, notPermutation, 0.0,
                          notPermutation == 0.0, "GATHER's order holds every particle once", "grid",
                          firstMissing(seen)});
    double cellsOutOfOrder = 0.0;
    std::string firstCell;
    const std::vector<std::uint32_t>& start = grid.cellStart;
    for (std::size_t c = 0; c + 1 < start.size(); ++c) {
        if (start[c] > start[c + 1] || start[c + 1] > n) {
            if (++cellsOutOfOrder == 1)
                firstCell = fmt::format("cell {}: offsets {} then {} (particles {})", c, start[c],
                                        start[c + 1], n);
            continue;
        }
        for (std::uint32_t k = start[c] + 1; k < start[c + 1]; ++k)
            if (grid.sorted[k - 1] >= grid.sorted[k]) {
                if (++cellsOutOfOrder == 1)
                    firstCell = fmt::format("cell {}: particle {} before particle {}", c,
                                            grid.sorted[k - 1], grid.sorted[k]);
                break;
            }
    }
    if (start.empty() || start.back() != n) {
        if (++cellsOutOfOrder == 1)
            firstCell = fmt::format("the last offset {} (particles {})",
                                    start.empty() ? 0u : start.back(), n);
    }
    out.checks.push_back({"grid_cells_out_of_order" + suffix, 0.0, cellsOutOfOrder, 0.0,
                          cellsOutOfOrder == 0.0,
                          "offsets rise to the count (scan.comp), each cell in index order (SORT)",
                          "grid", firstCell});
    double entriesWrong = 0.0;
    std::string firstEntry;
    for (std::size_t k = 0; k < n && k < grid.sorted.size(); ++k) {
        const std::uint32_t i = grid.sorted[k];
        if (grid.entryIndex[k] == i && i < n && grid.entryPosition[k] == ps.position[i]) continue;
        if (++entriesWrong == 1)
            firstEntry = fmt::format("slot {}: particle {}, entry index {} position {}{}", k, i,
                                     grid.entryIndex[k], vec3Text(grid.entryPosition[k]),
                                     i < n ? " cpu " + vec3Text(ps.position[i]) : "");
    }
    out.checks.push_back({"grid_entries_wrong" + suffix, 0.0, entriesWrong, 0.0,
                          entriesWrong == 0.0, "GATHER's entry: its particle's index, position",
                          "grid", firstEntry});
}

// The draw list after pack() (camera far from every sphere: nothing reaches the near plane)
// against the flags and radii: particle i is drawn where its radius is positive and (with
// culling) it is not hidden.
void checkDrawList(const GpuPerSet& g, const PerSetRequest& request, const std::string& suffix,
                   SelfCheck& out) {
    const std::vector<std::uint32_t> prefix = g.drawnPrefix();
    const std::vector<std::uint32_t> flags = g.flags();
    const std::vector<float> radii = g.radii();
    double wrong = 0.0;
    std::string first;
    for (std::size_t i = 0; i + 1 < prefix.size(); ++i) {
        const bool drawn = radii[i] > 0.0f && !(request.cull && (flags[i] & HIDDEN));
        if (prefix[i + 1] - prefix[i] == (drawn ? 1u : 0u)) continue;
        if (++wrong == 1)
            first = fmt::format("particle {}: prefix steps {} where it is {}drawn", i,
                                prefix[i + 1] - prefix[i], drawn ? "" : "not ");
    }
    const double total = prefix.empty() ? 0.0 : prefix.back();
    if (total != g.drawnCount() && ++wrong == 1)
        first = fmt::format("the prefix's total {} against the draw command's {}", total,
                            g.drawnCount());
    out.checks.push_back({"draw_list_wrong" + suffix, 0.0, wrong, 0.0, wrong == 0.0,
                          "MARK, the scan and FINISH: the prefix follows radii and flags",
                          "draw_list", first});
}

// The checks against the CPU's answers, and the first particles whose radius is apart.
void checkAnswers(const GpuPerSet& g, const core::ParticleSet& ps, const CpuAnswers& cpu,
                  const PerSetRequest& request, const std::string& suffix, SelfCheck& out) {
    const double n = static_cast<double>(ps.size());
    const std::vector<float> gpuRadii = g.radii();
    const std::vector<std::uint32_t> flags = g.flags();
    double apart = 0.0;
    std::string firstRadius;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        if (std::abs(gpuRadii[i] - cpu.radii[i]) <= 3e-4f * ps.h[i]) continue;
        if (apart == 0.0)
            firstRadius = fmt::format("particle {}: cpu {:g} gpu {:g} (h {:g})", i, cpu.radii[i],
                                      gpuRadii[i], ps.h[i]);
        if (++apart <= 5)
            out.notes.push_back(fmt::format(
                "radius apart{}: particle {} h {:g}: cpu {:g} gpu {:g} (flags {:#x}: {}{}{})",
                suffix, i, ps.h[i], cpu.radii[i], gpuRadii[i], flags[i],
                flags[i] & INTERIOR ? "settled by INTERIOR" : "walked by RADIUS",
                flags[i] & SPARSE ? ", sparse" : "", flags[i] & HIDDEN ? ", hidden" : ""));
    }
    out.checks.push_back({"radii_apart" + suffix, 0.0, apart, 0.0, apart == 0.0,
                          "particles whose radius differs over 3e-4 h", "radius", firstRadius});
    const std::vector<std::uint32_t> gpuVisible = request.cull ? g.visibleParticles() : cpu.visible;
    std::vector<std::uint32_t> onlyCpu, onlyGpu;
    std::set_difference(cpu.visible.begin(), cpu.visible.end(), gpuVisible.begin(),
                        gpuVisible.end(), std::back_inserter(onlyCpu));
    std::set_difference(gpuVisible.begin(), gpuVisible.end(), cpu.visible.begin(),
                        cpu.visible.end(), std::back_inserter(onlyGpu));
    auto firstOf = [](const std::vector<std::uint32_t>& v) {
        return v.empty() ? std::string() : fmt::format("particle {}", v.front());
    };
    out.checks.push_back({"hidden_on_gpu_only" + suffix, 0.0, double(onlyCpu.size()), n / 200,
                          double(onlyCpu.size()) <= n / 200, "at most 1 in 200", "cull",
                          firstOf(onlyCpu)});
    out.checks.push_back({"hidden_on_cpu_only" + suffix, 0.0, double(onlyGpu.size()), n / 100,
                          double(onlyGpu.size()) <= n / 100, "at most 1 in 100", "cull",
                          firstOf(onlyGpu)});
    const double drawn = g.drawnCount();
    out.checks.push_back({"stages_drawn" + suffix, cpu.drawn, drawn, n / 100,
                          std::abs(drawn - cpu.drawn) <= n / 100, "within 1 in 100", "draw_list",
                          ""});
}

}  // namespace

std::string firstStageApart(const SelfCheck& check, const std::string& suffix) {
    for (const SelfCheck::Check& c : check.checks) {
        const bool ofRun =
            suffix.empty() ? c.name.find(" (") == std::string::npos : c.name.ends_with(suffix);
        if (ofRun && !c.pass && !c.stage.empty())
            return fmt::format("{}: {}{}", c.stage, c.name.substr(0, c.name.size() - suffix.size()),
                               c.first.empty() ? "" : ": " + c.first);
    }
    return {};
}

SelfCheck perSetStageCheck(const core::SceneParticles& particles, const Settings& settings,
                           const glm::dvec3& camera) {
    core::SceneParticles withNormals = particles;
    if (!withNormals.hasNormals) core::deriveNormals(withNormals);
    // The second set: the first moved by one ulp along x (a new set to the GPU, the same
    // answers within the bounds).
    core::ParticleSet moved = withNormals.particles;
    for (glm::vec3& p : moved.position) p.x = std::nextafter(p.x, 1e30f);
    PerSetRequest request = perSetRequest(settings);
    request.droplets = false;  // impostorRadii's radii: no droplet members set to 0
    const core::ParticleSet& ps = withNormals.particles;
    const CpuAnswers cpu = cpuAnswers(ps, request), cpuMoved = cpuAnswers(moved, request);
    SelfCheck out;
    auto run = [&](GpuPerSet& g, ProgramCache& programs, const core::ParticleSet& set,
                   const CpuAnswers& answers, const std::string& suffix) {
        g.update(programs, set, request);
        g.pack(programs, {camera, 0.0});
        // In the order the stages run, so that the first failed check names the first stage
        // apart.
        checkUpload(g, set, suffix, out);
        checkLevels(g, set, suffix, out);
        checkGrid(g, set, suffix, out);
        checkAnswers(g, set, answers, request, suffix, out);
        checkDrawList(g, request, suffix, out);
        const std::string apart = firstStageApart(out, suffix);
        out.notes.push_back(
            fmt::format("first stage apart{}: {}", suffix, apart.empty() ? "none" : apart));
    };
    ProgramCache programs;
    GpuPerSet first;
    run(first, programs, ps, cpu, "");
    {
        GpuPerSet g;
        g.setStageClock(GpuPerSet::StageClock::Finish);
        run(g, programs, ps, cpu, " (glFinish)");
    }
    run(first, programs, moved, cpuMoved, " (kept buffers)");
    return out;
}

}  // namespace twinrender::realtime
