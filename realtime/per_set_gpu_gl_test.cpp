// realtime.per_set = "gpu" against the CPU path: the same answers per particle within float
// tolerances, the same frames, and the per-set work redone exactly when the set changes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/colour_field.h"
#include "core/install_layout.h"
#include "core/particles.h"
#include "core/scene.h"
#include "realtime/anisotropy.h"
#include "realtime/droplets.h"
#include "realtime/field_normal.h"
#include "realtime/gl/context.h"
#include "realtime/gpu_scene.h"
#include "realtime/impostor_radius.h"
#include "realtime/occlusion_culling.h"
#include "realtime/per_set_gpu.h"
#include "realtime/renderer.h"

namespace twinrender::realtime {
namespace {

// Two bodies in contact whose h differ by more than 2x (two levels of the grid), 2100
// particles: the contact scene made small.
struct Loaded {
    core::Scene scene;
    core::SceneParticles particles;    // as the renderer gets them: without normals
    core::SceneParticles withNormals;  // core::deriveNormals', for the CPU functions
    std::vector<core::Material> materials;
};

const Loaded& contact() {
    static const Loaded loaded = [] {
        Loaded l;
        const std::vector<std::string> overrides = {"bodies.left.particles=2000",
                                                    "bodies.right.particles=100",
                                                    "camera.width=160", "camera.height=120"};
        l.scene =
            core::loadScene((::twinrender::core::sourceDir() / "scenes/contact.toml"), overrides);
        l.particles = core::buildParticles(l.scene);
        l.withNormals = l.particles;
        core::deriveNormals(l.withNormals);
        l.materials = core::loadMaterials(l.scene);
        return l;
    }();
    return loaded;
}

class PerSetGpu : public ::testing::Test {
  protected:
    gl::Context context;
    ProgramCache programs;

    GpuPerSet built(const core::ParticleSet& ps, const PerSetRequest& request) {
        context.makeCurrent();
        GpuPerSet g;
        g.update(programs, ps, request);
        g.pack(programs, {glm::dvec3(0.0, -50.0, 0.0), 1e-3});
        return g;
    }
};

// A set without normals: the NORMALS pass derives core::deriveNormals' normals. Float sums of
// ~100 kernels in another order: rounding of ~1e-7 of the sum of the terms' sizes, which an
// interior particle's gradient (1e-3 of that sum where the neighbours nearly balance) turns
// into up to ~1e-3 rad (measured: 1.3e-3 at most, 40 of 2100 beyond 1e-4); a particle at the
// fallback's threshold may take the radial direction on one side only.
TEST_F(PerSetGpu, NormalsMatchCore) {
    const Loaded& l = contact();
    PerSetRequest request;
    context.makeCurrent();
    GpuPerSet g;
    g.update(programs, l.particles.particles, request, l.particles.bodies);
    EXPECT_GT(g.takeTimings().at("particle_normals"), 0.0);
    const std::vector<glm::vec3> gpu = g.normals();
    const std::vector<glm::vec3>& cpu = l.withNormals.particles.normal;
    ASSERT_EQ(gpu.size(), cpu.size());
    int apart = 0;
    for (std::size_t i = 0; i < cpu.size(); ++i) {
        EXPECT_NEAR(glm::length(gpu[i]), 1.0f, 1e-5f) << i;
        apart += !(glm::length(gpu[i] - cpu[i]) < 2e-3f);  // the chord: the angle, radians
    }
    EXPECT_LE(apart, static_cast<int>(cpu.size() / 200));
    // The radii from the GPU's normals are the CPU's (RadiiCullingAndFieldNormalsMatchTheCpu).
    const std::vector<float> cpuRadii = impostorRadii(l.withNormals.particles, request.particles);
    const std::vector<float> gpuRadii = g.radii();
    int radiiApart = 0;
    for (std::size_t i = 0; i < cpu.size(); ++i)
        radiiApart += !(std::abs(gpuRadii[i] - cpuRadii[i]) <= 3e-4f * l.particles.particles.h[i]);
    EXPECT_LE(radiiApart, apart);
}

// With culling, the particles INTERIOR settles (most of a body's) get their normals only where
// they may be drawn: every visible particle has core::deriveNormals' normal (as
// NormalsMatchCore), while hidden ones deep inside keep the fallback, the radial direction
// from their body's centre, unless that happens to be theirs too. The radii are the CPU's
// (interior_level on both paths).
TEST_F(PerSetGpu, InteriorParticlesGetTheirNormalsWhereTheyMayBeDrawn) {
    const Loaded& l = contact();
    PerSetRequest request;
    request.cull = true;
    context.makeCurrent();
    GpuPerSet g;
    g.update(programs, l.particles.particles, request, l.particles.bodies);
    const std::vector<glm::vec3> gpu = g.normals();
    const core::ParticleSet& cpu = l.withNormals.particles;
    const std::vector<std::uint32_t> visible = g.visibleParticles();
    ASSERT_LT(visible.size(), cpu.size() / 2);
    int visibleApart = 0;
    for (std::uint32_t i : visible) visibleApart += !(glm::length(gpu[i] - cpu.normal[i]) < 2e-3f);
    EXPECT_LE(visibleApart, static_cast<int>(visible.size() / 200));
    int fallback = 0;
    for (std::size_t i = 0; i < cpu.size(); ++i) {
        EXPECT_NEAR(glm::length(gpu[i]), 1.0f, 1e-5f) << i;
        const core::BodyInfo& body = l.particles.bodies[cpu.body[i]];
        const glm::vec3 radial = glm::normalize(glm::dvec3(cpu.position[i]) - body.center);
        fallback +=
            glm::length(gpu[i] - radial) < 1e-6f && !(glm::length(cpu.normal[i] - radial) < 2e-3f);
    }
    EXPECT_GT(fallback, static_cast<int>(cpu.size() / 4));  // their normals were not derived
    const std::vector<float> cpuRadii = impostorRadii(cpu, request.particles);
    const std::vector<float> gpuRadii = g.radii();
    for (std::size_t i = 0; i < cpu.size(); ++i)
        EXPECT_NEAR(gpuRadii[i], cpuRadii[i], 3e-4 * cpu.h[i]) << i;
}

TEST_F(PerSetGpu, RadiiCullingAndFieldNormalsMatchTheCpu) {
    const core::ParticleSet& ps = contact().withNormals.particles;
    ASSERT_GT(ps.h.back() / ps.h.front(), 2.0f);  // two levels of the grid
    PerSetRequest request;
    request.particles.normal = NormalModel::Field;
    request.cull = true;
    GpuPerSet g = built(ps, request);

    // Radii: the bisection stops within maxRadius / 8 / 2^10 = 1.1e-4 h of the crossing, and
    // float sums (relative error ~1e-6) move the crossing far less; 3e-4 h allows both paths'
    // brackets to end on either side.
    const std::vector<float> cpuRadii = impostorRadii(ps, request.particles);
    const std::vector<float> gpuRadii = g.radii();
    ASSERT_EQ(gpuRadii.size(), ps.size());
    int drawnWithSurface = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        EXPECT_NEAR(gpuRadii[i], cpuRadii[i], 3e-4 * ps.h[i]) << i;
        drawnWithSurface += cpuRadii[i] > 0.0f;
    }
    EXPECT_GT(drawnWithSurface, 2000);

    // Culling: both tests are exact with a margin, so they may differ only where a sphere is
    // covered within that margin; the GPU's hidden spheres must be hidden on the CPU too, up to
    // a few borderline ones, and it must cull about as many.
    const std::vector<std::uint32_t> cpuVisible = unoccludedParticles(ps, cpuRadii);
    const std::vector<std::uint32_t> gpuVisible = g.visibleParticles();
    std::vector<std::uint32_t> onlyCpu, onlyGpu;
    std::set_difference(cpuVisible.begin(), cpuVisible.end(), gpuVisible.begin(), gpuVisible.end(),
                        std::back_inserter(onlyCpu));
    std::set_difference(gpuVisible.begin(), gpuVisible.end(), cpuVisible.begin(), cpuVisible.end(),
                        std::back_inserter(onlyGpu));
    EXPECT_LT(cpuVisible.size(), ps.size() * 3 / 4);  // something is culled
    EXPECT_LE(onlyCpu.size(), ps.size() / 200) << "hidden on the GPU only";
    EXPECT_LE(onlyGpu.size(), ps.size() / 100) << "hidden on the CPU only";

    // Field normal models, all particles: the direction of the modelled normal at the
    // impostor's outward point and at a point beside it. Float sums of ~100 kernels: 1e-3 rad.
    const std::vector<FieldNormal> cpu = fieldNormals(ps, cpuRadii);
    const std::vector<glm::vec4> gpu = g.models();
    ASSERT_EQ(gpu.size(), 3 * ps.size());
    for (std::size_t i = 0; i < ps.size(); ++i) {
        if (!(cpuRadii[i] > 0.0f)) continue;
        auto normalAt = [&](glm::vec3 outward, glm::vec3 d, glm::vec3 o, glm::vec3 x) {
            const glm::mat3 h(d.x, o.x, o.y, o.x, d.y, o.z, o.y, o.z, d.z);
            return glm::normalize(outward + h * x);
        };
        const glm::vec3 top = cpuRadii[i] * ps.normal[i];
        const glm::vec3 side =
            0.5f * cpuRadii[i] * glm::normalize(glm::cross(ps.normal[i], {0.3f, 0.5f, 0.8f}));
        for (const glm::vec3& x : {top, top + side}) {
            const glm::vec3 a = normalAt(cpu[i].outward, cpu[i].diagonal, cpu[i].offDiagonal, x);
            const glm::vec3 b = normalAt(glm::vec3(gpu[3 * i]), glm::vec3(gpu[3 * i + 1]),
                                         glm::vec3(gpu[3 * i + 2]), x);
            EXPECT_GT(glm::dot(a, b), std::cos(1e-3f)) << i;
        }
    }
}

// The stage clock: on llvmpipe, whose timer queries read 1 ns around compute, the probe takes
// the wall clock; forced to timer queries, the same stages are timed (each read after the
// work, whatever it reads) and the answers do not change.
TEST_F(PerSetGpu, StagesAreTimedByQueriesOnlyWhereTheySeeCompute) {
    const core::ParticleSet& ps = contact().withNormals.particles;
    PerSetRequest request;
    request.cull = true;
    context.makeCurrent();
    std::map<std::string, double> timings[2];
    std::vector<float> radii[2];
    std::vector<std::uint32_t> visible[2];
    for (int queries : {0, 1}) {
        GpuPerSet g;
        if (queries) g.setStageClock(GpuPerSet::StageClock::Queries);
        g.update(programs, ps, request);
        g.pack(programs, {glm::dvec3(0.0, -50.0, 0.0), 1e-3});
        timings[queries] = g.takeTimings();
        radii[queries] = g.radii();
        visible[queries] = g.visibleParticles();
        if (!queries && context.renderer().find("llvmpipe") != std::string::npos) {
            EXPECT_EQ(g.stageClock(), GpuPerSet::StageClock::Finish);
            for (const char* stage : {"grid", "radius", "cull", "pack"})
                EXPECT_GT(timings[0].at(stage), 0.0) << stage;
        }
        EXPECT_TRUE(g.takeTimings().empty()) << "the queries are read once";
    }
    ASSERT_EQ(timings[0].size(), timings[1].size());
    for (const auto& [stage, ms] : timings[1]) {
        EXPECT_TRUE(timings[0].contains(stage)) << stage;
        EXPECT_GE(ms, 0.0) << stage;
    }
    EXPECT_EQ(radii[0], radii[1]);
    EXPECT_EQ(visible[0], visible[1]);
}

TEST_F(PerSetGpu, EllipsoidsMatchTheCpu) {
    const core::ParticleSet& ps = contact().withNormals.particles;
    PerSetRequest request;
    request.particles.shape = ParticleShape::Ellipsoid;
    GpuPerSet g = built(ps, request);
    const std::vector<float> radii = impostorRadii(ps, request.particles);
    const std::vector<Ellipsoid> cpu =
        anisotropicEllipsoids(ps, radii, request.particles.anisotropy);
    const std::vector<glm::vec4> gpu = g.models();
    ASSERT_EQ(gpu.size(), 3 * ps.size());
    int stretched = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        // A A^T (the ellipsoid's quadric, whatever the order or sign of the eigenvectors) and
        // the shift, relative to the radius: float covariance and Jacobi rotations, 2e-3 r
        // (eigenvalues within rounding of each other have ill-defined eigenvectors but the same
        // quadric).
        glm::mat3 a, b;
        glm::vec3 shiftA, shiftB;
        for (int k = 0; k < 3; ++k) {
            a[k] = cpu[i].axes[k];
            b[k] = glm::vec3(gpu[3 * i + k]);
            shiftA[k] = cpu[i].shift[k];
            shiftB[k] = gpu[3 * i + k].w;
        }
        const glm::mat3 qa = a * glm::transpose(a), qb = b * glm::transpose(b);
        const float r = std::max(radii[i], 1e-6f);
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(qa[c][k], qb[c][k], 2e-3f * r * r) << i;
        EXPECT_LT(glm::length(shiftA - shiftB), 2e-3f * r) << i;
        stretched += !cpu[i].isSphere();
    }
    EXPECT_GT(stretched, 1000);
}

// The frame of a new particle set redoes the per-set work (counters.per_set_builds = 1); a
// frame of the same set reuses it (0), on both paths, and the two paths' frames agree.
// Culling holds only where no drawn sphere reaches into the near plane's ball: then every
// particle with a surface is drawn. A camera far from the particles' box skips the test
// (NEAR); one outside the box but within a sphere's reach of it, or inside, takes it.
TEST_F(PerSetGpu, CullingIsOffForFramesWhoseNearPlaneCutsASphere) {
    const core::ParticleSet& ps = contact().withNormals.particles;
    PerSetRequest request;
    request.cull = true;
    GpuPerSet g = built(ps, request);
    const std::vector<float> radii = g.radii();
    const auto withSurface = static_cast<std::uint32_t>(
        std::count_if(radii.begin(), radii.end(), [](float r) { return r > 0.0f; }));
    std::uint32_t visible = 0;  // not hidden, with a surface
    for (std::uint32_t i : g.visibleParticles()) visible += radii[i] > 0.0f;
    ASSERT_LT(visible, withSurface * 3 / 4);  // culling hides many of them
    EXPECT_EQ(g.drawnCount(), visible);       // the camera 50 units away (built())

    // The particle farthest along +x, and a camera just beyond its sphere.
    std::size_t edge = 0;
    for (std::size_t i = 0; i < ps.size(); ++i)
        if (radii[i] > 0.0f && ps.position[i].x > ps.position[edge].x) edge = i;
    const glm::dvec3 x(ps.position[edge]);
    const double reach = 1e-3;
    g.pack(programs, {x + glm::dvec3(radii[edge] + 2.0 * reach, 0.0, 0.0), reach});
    EXPECT_EQ(g.drawnCount(), visible) << "a sphere's width outside: culled";
    g.pack(programs, {x + glm::dvec3(radii[edge] + 0.5 * reach, 0.0, 0.0), reach});
    EXPECT_EQ(g.drawnCount(), withSurface) << "the near plane's ball reaches a sphere";
    g.pack(programs, {x, reach});
    EXPECT_EQ(g.drawnCount(), withSurface) << "inside a sphere";
    g.pack(programs, {glm::dvec3(0.0, -50.0, 0.0), reach});
    EXPECT_EQ(g.drawnCount(), visible) << "far again";
}

// A steady frame keeps the marks (drawn particles, their prefix) of the frame before where nothing
// they depend on changed, and its records equal those of marks made anew; a camera whose near
// plane's ball may reach a sphere makes them anew, and so does every frame until the levels'
// boxes are known (afterFrame) and after a new set.
TEST_F(PerSetGpu, SteadyFramesKeepTheMarksAndDrawTheSame) {
    const core::ParticleSet& ps = contact().withNormals.particles;
    PerSetRequest request;
    request.cull = true;
    const FrameRequest far{glm::dvec3(0.0, -50.0, 0.0), 1e-3};
    const FrameRequest farther{glm::dvec3(3.0, -60.0, 1.0), 1e-3};
    GpuPerSet fresh = built(ps, request);
    fresh.pack(programs, farther);
    const std::uint32_t drawn = fresh.drawnCount();
    const std::vector<GpuParticle> expected = fresh.particles().read<GpuParticle>(0, drawn);
    const std::vector<std::uint32_t> prefix = fresh.drawnPrefix();
    ASSERT_GT(drawn, 0u);

    GpuPerSet g = built(ps, request);
    g.pack(programs, far);
    EXPECT_FALSE(g.marksReused()) << "the boxes are not known before a frame is done";
    g.afterFrame();
    g.pack(programs, farther);
    EXPECT_TRUE(g.marksReused());
    EXPECT_EQ(g.drawnCount(), drawn);
    EXPECT_EQ(g.drawnPrefix(), prefix);
    const std::vector<GpuParticle> kept = g.particles().read<GpuParticle>(0, drawn);
    EXPECT_EQ(std::memcmp(kept.data(), expected.data(), drawn * sizeof(GpuParticle)), 0)
        << "the records are relative to this frame's camera";

    // Inside the body: NEAR decides, the marks are made anew (culling off).
    g.pack(programs, {glm::dvec3(ps.position[0]), 1e-3});
    EXPECT_FALSE(g.marksReused());
    EXPECT_GT(g.drawnCount(), drawn);
    g.pack(programs, far);
    EXPECT_FALSE(g.marksReused()) << "marks made near are not a far frame's";
    EXPECT_EQ(g.drawnCount(), drawn);
    g.pack(programs, far);
    EXPECT_TRUE(g.marksReused());

    // A new set (one particle moved by an ulp): everything anew.
    core::ParticleSet moved = ps;
    moved.position[0].x = std::nextafter(moved.position[0].x, 1e30f);
    g.update(programs, moved, request);
    g.pack(programs, far);
    EXPECT_FALSE(g.marksReused());
}

// normal = "gradient", per_set = "gpu": the normal gathered through the grid at each covered
// pixel is the colour field's exact one at the surface point the G-buffer holds there
// (core::ColourField, every particle, in double): within 0.01 degrees (measured: 1.6e-4),
// float sums of ~100 kernels. per_set = "cpu" splats the kernels surfaceKernels keeps, a
// subset that misses some at the contact between the two bodies (3.4 degrees there); a sum over a
// wrong neighbourhood (a cell missed, a kernel twice, the wrong support) would be degrees off.
TEST_F(PerSetGpu, GatheredGradientNormalsAreTheFieldsExactOnes) {
    const Loaded& l = contact();
    Device device(context);
    Settings s;
    s.perSet = PerSetDevice::Gpu;
    s.particles.normal = NormalModel::Gradient;
    s.surface.method = SurfaceMethod::None;  // the G-buffer's normals, not smoothed ones
    Renderer renderer(device, s);
    const core::Frame frame = renderer.render({l.scene, l.particles, l.materials});
    const core::Image& image = frame.image;
    const core::Camera camera(l.scene.camera);
    const core::ColourField field(l.particles.particles);
    const int alpha = image.requireChannel("A"), depth = image.requireChannel("Z"),
              nx = image.requireChannel("N.X"), ny = image.requireChannel("N.Y"),
              nz = image.requireChannel("N.Z");
    double worst = 0.0;
    int covered = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            if (!(image.at(x, y, alpha) > 0.5f)) continue;
            ++covered;
            const core::Ray ray = camera.ray(x + 0.5, y + 0.5);
            const glm::dvec3 point =
                ray.origin + ray.direction * (double(image.at(x, y, depth)) /
                                              glm::dot(ray.direction, camera.forward()));
            const glm::dvec3 exact = -glm::normalize(field.derivatives(point).gradient);
            const glm::dvec3 n(image.at(x, y, nx), image.at(x, y, ny), image.at(x, y, nz));
            const double cosine = glm::dot(exact, n) / glm::length(n);
            worst = std::max(worst, std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / M_PI);
        }
    ASSERT_GT(covered, 1000);
    EXPECT_LT(worst, 0.01) << "degrees";
    std::cout << "[ gather ] " << covered << " pixels, worst " << worst << " degrees\n";
}

TEST_F(PerSetGpu, PerSetWorkIsRedoneExactlyWhenTheSetChanges) {
    Loaded l = contact();
    Device device(context);
    core::Frame frames[2];
    for (PerSetDevice where : {PerSetDevice::Gpu, PerSetDevice::Cpu}) {
        Settings s;
        s.perSet = where;
        s.bloom.enabled = false;
        Renderer renderer(device, s);
        const core::Frame first = renderer.render({l.scene, l.particles, l.materials});
        EXPECT_EQ(first.counters.at("per_set_builds"), 1.0) << toString(where);
        EXPECT_GT(first.timingsMs.at("radius"), 0.0);
        EXPECT_GT(first.timingsMs.at("particle_normals"), 0.0);  // the set came without normals
        const core::Frame again = renderer.render({l.scene, l.particles, l.materials});
        EXPECT_EQ(again.counters.at("per_set_builds"), 0.0) << toString(where);
        if (where == PerSetDevice::Gpu) {
            EXPECT_EQ(again.timingsMs.at("radius"), 0.0);
            EXPECT_EQ(again.timingsMs.at("particle_normals"), 0.0);
        }
        EXPECT_EQ(again.counters.at("particles_drawn"), first.counters.at("particles_drawn"));
        core::SceneParticles moved = l.particles;
        moved.particles.position[7].x += 1e-3f;  // one particle moves: a new set
        const core::Frame next = renderer.render({l.scene, moved, l.materials});
        EXPECT_EQ(next.counters.at("per_set_builds"), 1.0) << toString(where);
        frames[where == PerSetDevice::Gpu ? 0 : 1] =
            renderer.render({l.scene, l.particles, l.materials});
    }
    // The same frame from either path: coverage and id identical but for a few outline pixels
    // (radii within 3e-4 h), and so is the beauty (within 1e-2) but for a few pixels whose
    // front particle changed.
    const core::Image& g = frames[0].image;
    const core::Image& c = frames[1].image;
    const int alpha = g.requireChannel("A"), id = g.requireChannel("id"),
              red = g.requireChannel("R");
    int differ = 0, covered = 0, shadedApart = 0;
    for (int y = 0; y < g.height(); ++y)
        for (int x = 0; x < g.width(); ++x) {
            covered += c.at(x, y, alpha) > 0.5f;
            if (g.at(x, y, alpha) != c.at(x, y, alpha) || g.at(x, y, id) != c.at(x, y, id)) {
                ++differ;
                continue;
            }
            if (c.at(x, y, alpha) > 0.5f)
                shadedApart += std::abs(g.at(x, y, red) - c.at(x, y, red)) > 1e-2f;
        }
    EXPECT_GT(covered, 2000);
    EXPECT_LE(differ, covered / 200);
    EXPECT_LE(shadedApart, covered / 200);
}

// Frame 40 of the LAMMPS splash (scenes/splash_droplets.toml): a sheet broken into droplets,
// 174 of them small clusters drawn as one ellipsoid each, beside bodies that cull their
// hidden particles.
TEST_F(PerSetGpu, DropletFramesMatchTheCpu) {
    Loaded l;
    l.scene =
        core::loadScene((::twinrender::core::sourceDir() / "scenes/splash_droplets.toml"), {});
    l.particles = core::buildParticles(l.scene);
    l.materials = core::loadMaterials(l.scene);
    Device device(context);
    for (NormalModel normal : {NormalModel::Gradient, NormalModel::Field}) {
        core::Frame frames[2];
        for (PerSetDevice where : {PerSetDevice::Gpu, PerSetDevice::Cpu}) {
            Settings s;
            s.perSet = where;
            s.particles.normal = normal;
            s.bloom.enabled = false;
            Renderer renderer(device, s);
            frames[where == PerSetDevice::Gpu ? 0 : 1] =
                renderer.render({l.scene, l.particles, l.materials});
        }
        const core::Frame& g = frames[0];
        const core::Frame& c = frames[1];
        EXPECT_EQ(c.counters.at("droplets"), 174.0);
        EXPECT_EQ(g.counters.at("droplets"), c.counters.at("droplets"));
        // Radii within 3e-4 h: a particle or two may change sides of the culling test.
        EXPECT_NEAR(g.counters.at("particles_drawn"), c.counters.at("particles_drawn"), 3.0);
        // The same image but for a few outline pixels (the radii) and pixels whose front
        // particle changed; a droplet's field normal model is its ellipsoid's on both paths,
        // so the shading agrees within 1e-2.
        const int alpha = g.image.requireChannel("A"), id = g.image.requireChannel("id"),
                  red = g.image.requireChannel("R");
        int differ = 0, covered = 0, shadedApart = 0;
        for (int y = 0; y < g.image.height(); ++y)
            for (int x = 0; x < g.image.width(); ++x) {
                covered += c.image.at(x, y, alpha) > 0.5f;
                if (g.image.at(x, y, alpha) != c.image.at(x, y, alpha) ||
                    g.image.at(x, y, id) != c.image.at(x, y, id)) {
                    ++differ;
                    continue;
                }
                if (c.image.at(x, y, alpha) > 0.5f)
                    shadedApart += std::abs(g.image.at(x, y, red) - c.image.at(x, y, red)) > 1e-2f;
            }
        EXPECT_GT(covered, 5000);
        EXPECT_LE(differ, covered / 200) << toString(normal);
        EXPECT_LE(shadedApart, covered / 200) << toString(normal);
    }
}

// The droplet stages fit, on the same frame, the droplets fitDroplets fits on the CPU from the
// GPU's own radii: the same first particles, the same radii elsewhere (the members' 0), and
// ellipsoids within 1e-3 h of the CPU's. The crossings' last bracket is the cluster's reach
// (about 3 h) / 8192; where the float and double sums disagree about a sample's side of the
// level the answer moves by that much (measured: 3e-4 h at most).
TEST_F(PerSetGpu, DropletStagesFitTheCpusDroplets) {
    const core::Scene scene =
        core::loadScene((::twinrender::core::sourceDir() / "scenes/splash_droplets.toml"), {});
    const core::SceneParticles particles = core::buildParticles(scene);
    ASSERT_FALSE(particles.hasNormals);
    const core::ParticleSet& ps = particles.particles;
    const ParticleSettings settings;
    PerSetRequest request;
    request.particles = settings;
    context.makeCurrent();
    GpuPerSet spheres;  // no droplets: the radii they are fitted from
    spheres.update(programs, ps, request, particles.bodies);
    EXPECT_TRUE(spheres.droplets().empty());
    const Droplets cpu =
        fitDroplets(ps, spheres.radii(), settings.surfaceLevel, settings.dropletAtoms);
    request.droplets = true;
    GpuPerSet g;
    g.update(programs, ps, request, particles.bodies);
    EXPECT_GT(g.takeTimings().at("droplets"), 0.0);
    const auto gpu = g.droplets();
    ASSERT_EQ(gpu.size(), 174u);
    ASSERT_EQ(g.dropletCount(), 174u);
    ASSERT_EQ(cpu.firsts.size(), gpu.size());
    for (std::size_t k = 0; k < gpu.size(); ++k) {
        const auto& [first, e] = gpu[k];
        ASSERT_EQ(first, cpu.firsts[k]);
        const Ellipsoid& c = cpu.ellipsoids[first];
        const float tolerance = 1e-3f * ps.h[first];
        for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(e.shift[a], c.shift[a], tolerance) << first;
            EXPECT_LT(glm::length(e.axes[a] - c.axes[a]), tolerance) << first << " axis " << a;
        }
    }
    const std::vector<float> radii = g.radii();
    for (std::size_t i = 0; i < ps.size(); ++i)
        EXPECT_NEAR(radii[i], cpu.radii[i], 1e-3f * ps.h[i]) << i;
}

}  // namespace
}  // namespace twinrender::realtime
