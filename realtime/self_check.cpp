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
        out += fmt::format("  {:<26} cpu {:>10g}  gpu {:>10g}  bound {:>8g}  {}  ({})\n", c.name,
                           c.cpu, c.gpu, c.bound, c.pass ? "pass" : "FAIL", c.why);
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
    if (usesKernels(settings)) {
        const double c = counter(cpu, "kernels_splatted"), g = counter(gpu, "kernels_splatted");
        add("kernels_splatted", c, g, 4.0 * c, g >= c && g <= 4.0 * c,
            "the GPU's at least the CPU's, at most 4 times");
    }
    const ImageDifference d = imageDifference(cpu, gpu);
    const double bound = std::max(d.covered / 200, 1);
    add("covered_pixels", d.covered, d.covered, 1.0, d.covered > 0, "something drawn");
    add("coverage_or_body_apart", 0.0, d.apart, bound, d.apart <= bound,
        "pixels, at most 1 in 200 covered");
    add("shading_apart", 0.0, d.shadedApart, bound, d.shadedApart <= bound,
        "covered pixels whose red differs over 1e-2, at most 1 in 200");
    return out;
}

SelfCheck perSetStageCheck(const core::SceneParticles& particles, const Settings& settings,
                           const glm::dvec3& camera) {
    core::SceneParticles withNormals = particles;
    if (!withNormals.hasNormals) core::deriveNormals(withNormals);
    const core::ParticleSet& ps = withNormals.particles;
    PerSetRequest request = perSetRequest(settings);
    request.droplets = false;  // impostorRadii's radii: no droplet members set to 0
    const std::vector<float> cpuRadii = impostorRadii(ps, request.particles);
    std::vector<std::uint32_t> cpuVisible;
    if (request.cull) {
        cpuVisible = unoccludedParticles(ps, cpuRadii);
    } else {
        for (std::size_t i = 0; i < ps.size(); ++i) cpuVisible.push_back(std::uint32_t(i));
    }
    double cpuDrawn = 0.0;
    for (std::uint32_t i : cpuVisible) cpuDrawn += cpuRadii[i] > 0.0f;
    const double n = static_cast<double>(ps.size());
    SelfCheck out;
    for (const bool finish : {false, true}) {
        ProgramCache programs;
        GpuPerSet g;
        if (finish) g.setStageClock(GpuPerSet::StageClock::Finish);
        g.update(programs, ps, request);
        g.pack(programs, {camera, 0.0});
        const std::string clock = finish ? " (glFinish)" : "";
        const std::vector<float> gpuRadii = g.radii();
        double apart = 0.0;
        for (std::size_t i = 0; i < ps.size(); ++i)
            apart += !(std::abs(gpuRadii[i] - cpuRadii[i]) <= 3e-4f * ps.h[i]);
        out.checks.push_back({"radii_apart" + clock, 0.0, apart, 0.0, apart == 0.0,
                              "particles whose radius differs over 3e-4 h"});
        const std::vector<std::uint32_t> gpuVisible =
            request.cull ? g.visibleParticles() : cpuVisible;
        std::vector<std::uint32_t> onlyCpu, onlyGpu;
        std::set_difference(cpuVisible.begin(), cpuVisible.end(), gpuVisible.begin(),
                            gpuVisible.end(), std::back_inserter(onlyCpu));
        std::set_difference(gpuVisible.begin(), gpuVisible.end(), cpuVisible.begin(),
                            cpuVisible.end(), std::back_inserter(onlyGpu));
        out.checks.push_back({"hidden_on_gpu_only" + clock, 0.0, double(onlyCpu.size()), n / 200,
                              double(onlyCpu.size()) <= n / 200, "at most 1 in 200"});
        out.checks.push_back({"hidden_on_cpu_only" + clock, 0.0, double(onlyGpu.size()), n / 100,
                              double(onlyGpu.size()) <= n / 100, "at most 1 in 100"});
        const double drawn = g.drawnCount();
        out.checks.push_back({"stages_drawn" + clock, cpuDrawn, drawn, n / 100,
                              std::abs(drawn - cpuDrawn) <= n / 100, "within 1 in 100"});
    }
    return out;
}

}  // namespace twinrender::realtime
