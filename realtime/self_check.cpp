#include "realtime/self_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>

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
                          notPermutation == 0.0, "GATHER's order holds every particle once"});
    double cellsOutOfOrder = 0.0;
    const std::vector<std::uint32_t>& start = grid.cellStart;
    for (std::size_t c = 0; c + 1 < start.size(); ++c) {
        if (start[c] > start[c + 1] || start[c + 1] > n) {
            ++cellsOutOfOrder;
            continue;
        }
        for (std::uint32_t k = start[c] + 1; k < start[c + 1]; ++k)
            if (grid.sorted[k - 1] >= grid.sorted[k]) {
                ++cellsOutOfOrder;
                break;
            }
    }
    if (start.empty() || start.back() != n) ++cellsOutOfOrder;
    out.checks.push_back(
        {"grid_cells_out_of_order" + suffix, 0.0, cellsOutOfOrder, 0.0, cellsOutOfOrder == 0.0,
         "offsets rise to the count (scan.comp), each cell in index order (SORT)"});
    double entriesWrong = 0.0;
    for (std::size_t k = 0; k < n && k < grid.sorted.size(); ++k) {
        const std::uint32_t i = grid.sorted[k];
        entriesWrong +=
            grid.entryIndex[k] != i || i >= n || grid.entryPosition[k] != ps.position[i];
    }
    out.checks.push_back({"grid_entries_wrong" + suffix, 0.0, entriesWrong, 0.0,
                          entriesWrong == 0.0, "GATHER's entry: its particle's index, position"});
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
    for (std::size_t i = 0; i + 1 < prefix.size(); ++i) {
        const bool drawn = radii[i] > 0.0f && !(request.cull && (flags[i] & HIDDEN));
        wrong += prefix[i + 1] - prefix[i] != (drawn ? 1u : 0u);
    }
    const double total = prefix.empty() ? 0.0 : prefix.back();
    if (total != g.drawnCount()) ++wrong;
    out.checks.push_back({"draw_list_wrong" + suffix, 0.0, wrong, 0.0, wrong == 0.0,
                          "MARK, the scan and FINISH: the prefix follows radii and flags"});
}

// The checks against the CPU's answers, and the first particles whose radius is apart.
void checkAnswers(const GpuPerSet& g, const core::ParticleSet& ps, const CpuAnswers& cpu,
                  const PerSetRequest& request, const std::string& suffix, SelfCheck& out) {
    const double n = static_cast<double>(ps.size());
    const std::vector<float> gpuRadii = g.radii();
    const std::vector<std::uint32_t> flags = g.flags();
    double apart = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        if (std::abs(gpuRadii[i] - cpu.radii[i]) <= 3e-4f * ps.h[i]) continue;
        if (++apart <= 5)
            out.notes.push_back(fmt::format(
                "radius apart{}: particle {} h {:g}: cpu {:g} gpu {:g} (flags {:#x}: {}{}{})",
                suffix, i, ps.h[i], cpu.radii[i], gpuRadii[i], flags[i],
                flags[i] & INTERIOR ? "settled by INTERIOR" : "walked by RADIUS",
                flags[i] & SPARSE ? ", sparse" : "", flags[i] & HIDDEN ? ", hidden" : ""));
    }
    out.checks.push_back({"radii_apart" + suffix, 0.0, apart, 0.0, apart == 0.0,
                          "particles whose radius differs over 3e-4 h"});
    const std::vector<std::uint32_t> gpuVisible = request.cull ? g.visibleParticles() : cpu.visible;
    std::vector<std::uint32_t> onlyCpu, onlyGpu;
    std::set_difference(cpu.visible.begin(), cpu.visible.end(), gpuVisible.begin(),
                        gpuVisible.end(), std::back_inserter(onlyCpu));
    std::set_difference(gpuVisible.begin(), gpuVisible.end(), cpu.visible.begin(),
                        cpu.visible.end(), std::back_inserter(onlyGpu));
    out.checks.push_back({"hidden_on_gpu_only" + suffix, 0.0, double(onlyCpu.size()), n / 200,
                          double(onlyCpu.size()) <= n / 200, "at most 1 in 200"});
    out.checks.push_back({"hidden_on_cpu_only" + suffix, 0.0, double(onlyGpu.size()), n / 100,
                          double(onlyGpu.size()) <= n / 100, "at most 1 in 100"});
    const double drawn = g.drawnCount();
    out.checks.push_back({"stages_drawn" + suffix, cpu.drawn, drawn, n / 100,
                          std::abs(drawn - cpu.drawn) <= n / 100, "within 1 in 100"});
}

}  // namespace

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
        checkGrid(g, set, suffix, out);
        checkDrawList(g, request, suffix, out);
        checkAnswers(g, set, answers, request, suffix, out);
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
