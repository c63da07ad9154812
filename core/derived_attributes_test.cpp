#include "core/derived_attributes.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <numbers>
#include <vector>

#include "core/blackbody.h"
#include "core/error.h"
#include "core/install_layout.h"
#include "core/particle_generators.h"
#include "core/particles.h"
#include "core/scene.h"
#include "core/sph_kernel.h"
#include "tests/scratch_dir.h"

namespace twinrender::core {
namespace {

// The particles with their normals, which buildParticles leaves to their user.
SceneParticles builtWithNormals(const Scene& scene) {
    SceneParticles sp = buildParticles(scene);
    deriveNormals(sp);
    return sp;
}

constexpr double PI = std::numbers::pi;

double degreesBetween(const glm::dvec3& a, const glm::dvec3& b) {
    const double c = glm::dot(glm::normalize(a), glm::normalize(b));
    return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / PI;
}

double luminance(const glm::vec3& rgb) {
    return 0.2126729 * rgb.r + 0.7151522 * rgb.g + 0.0721750 * rgb.b;
}

Scene sceneWith(std::vector<BodyDesc> bodies) {
    Scene s;
    s.name = "test";
    s.bodies = std::move(bodies);
    return s;
}

BodyDesc ballBody(std::int64_t n, Lattice lattice = Lattice::Hcp) {
    BodyDesc b;
    b.name = "ball";
    b.radius = 1.0;
    b.particles = n;
    b.lattice = lattice;
    return b;
}

// ---- uv ----------------------------------------------------------------------------------

// u differences across the seam: the shorter way round.
double wrapDelta(double du) {
    return du - std::round(du);
}

TEST(SphericalUv, GradientMatchesFiniteDifferences) {
    SplitMix64 rng(42);
    auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniform(); };
    int tested = 0;
    for (int t = 0; t < 2000; ++t) {
        const glm::dvec3 center(uniform(-2, 2), uniform(-2, 2), uniform(-2, 2));
        const glm::dmat3 frame = bodyFrame({uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)});
        const glm::dvec3 x = center + glm::dvec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
        const glm::dvec3 local = glm::transpose(frame) * (x - center);
        const double rho = std::hypot(local.x, local.y);
        if (rho < 0.05) continue;  // near the pole axis the gradient of u is singular
        ++tested;
        const SphericalUv s = sphericalUv(x, center, frame);
        const double eps = 1e-6;
        for (int k = 0; k < 3; ++k) {
            glm::dvec3 e(0.0);
            e[k] = eps;
            const SphericalUv p = sphericalUv(x + e, center, frame);
            const SphericalUv m = sphericalUv(x - e, center, frame);
            const double du = wrapDelta(p.uv.x - m.uv.x) / (2 * eps);
            const double dv = (p.uv.y - m.uv.y) / (2 * eps);
            // Central differences: error ~ eps^2 f''' + rounding 1e-16 / eps ~ 1e-9 here.
            EXPECT_NEAR(s.dudx[k], du, 1e-6 * (1.0 + std::abs(du))) << "t=" << t << " k=" << k;
            EXPECT_NEAR(s.dvdx[k], dv, 1e-6 * (1.0 + std::abs(dv))) << "t=" << t << " k=" << k;
        }
    }
    EXPECT_GT(tested, 1000);
}

TEST(SphericalUv, RangesPolesAndAxis) {
    const glm::dmat3 frame(1.0);
    const glm::dvec3 c(0.0);
    EXPECT_NEAR(sphericalUv({0, 0, 1}, c, frame).uv.y, 1.0, 1e-12);   // north pole
    EXPECT_NEAR(sphericalUv({0, 0, -1}, c, frame).uv.y, 0.0, 1e-12);  // south pole
    EXPECT_NEAR(sphericalUv({1, 0, 0}, c, frame).uv.y, 0.5, 1e-12);   // equator
    EXPECT_NEAR(sphericalUv({0, 1, 0}, c, frame).uv.x, 0.25, 1e-12);  // 90 degrees east
    EXPECT_NEAR(sphericalUv({-1, 0, 0}, c, frame).uv.x, 0.5, 1e-12);
    // On the pole axis (and at the centre) the gradients are 0.
    for (const glm::dvec3 p : {glm::dvec3(0, 0, 2), glm::dvec3(0, 0, -0.5), glm::dvec3(0.0)}) {
        const SphericalUv s = sphericalUv(p, c, frame);
        EXPECT_EQ(s.dudx, glm::dvec3(0.0));
        EXPECT_EQ(s.dvdx, glm::dvec3(0.0));
    }
}

TEST(SphericalUv, UWrapsAtTheSeam) {
    // The seam is the local +x half plane; longitude grows toward +y (east).
    ParticleSet set;
    set.resize(2);
    const double a = 1e-4;                                         // radians
    set.position[0] = glm::vec3(std::cos(a), -std::sin(a), 0.0f);  // just west of the seam
    set.position[1] = glm::vec3(std::cos(a), std::sin(a), 0.0f);   // just east of it
    BodyInfo body;
    body.end = 2;
    deriveUv(set, body, false);
    EXPECT_GT(set.uv[0].x, 0.999f);
    EXPECT_LT(set.uv[0].x, 1.0f);
    EXPECT_LT(set.uv[1].x, 0.001f);
    EXPECT_GE(set.uv[1].x, 0.0f);
    // Both see the same gradient direction (east): u is continuous modulo 1.
    EXPECT_GT(glm::dot(set.dudx[0], set.dudx[1]), 0.0f);

    // A point so close to the seam that u rounds to 1.0f stores 0.
    set.position[0] = glm::vec3(1.0f, -1e-9f, 0.0f);
    deriveUv(set, body, false);
    EXPECT_GE(set.uv[0].x, 0.0f);
    EXPECT_LT(set.uv[0].x, 1.0f);
}

TEST(SphericalUv, FileUvIsKeptAndWrapped) {
    ParticleSet set;
    set.resize(2);
    set.position[0] = glm::vec3(1, 0.5f, 0.2f);
    set.position[1] = glm::vec3(-1, 0.5f, 0.2f);
    set.uv[0] = glm::vec2(0.3f, 0.7f);
    set.uv[1] = glm::vec2(1.25f, 0.1f);
    BodyInfo body;
    body.end = 2;
    deriveUv(set, body, true);
    EXPECT_EQ(set.uv[0], glm::vec2(0.3f, 0.7f));
    EXPECT_NEAR(set.uv[1].x, 0.25f, 1e-6f);
    EXPECT_EQ(set.uv[1].y, 0.1f);
    const SphericalUv s = sphericalUv(glm::dvec3(set.position[0]), body.center, body.frame);
    EXPECT_EQ(set.dudx[0], glm::vec3(s.dudx));
}

// ---- normals -----------------------------------------------------------------------------

// The normal of a lattice particle is the colour-field gradient at the particle, so it sees
// the lattice's facets: on the terraces of an hcp ball it follows the facet, not the sphere.
// Measured for a 20000-particle hcp ball, over the outermost particles (r > R - s/2): median
// ~6 degrees, 95th percentile ~13, maximum ~18 (the same at 1M: the facets scale with s).
TEST(Normals, BallSurfaceNormalsPointOutward) {
    const SceneParticles sp = builtWithNormals(sceneWith({ballBody(20000)}));
    const ParticleSet& p = sp.particles;
    const double s = latticeSpacing(ballBody(20000));
    std::vector<double> angles;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const glm::dvec3 x(p.position[i]);
        if (glm::length(x) > 1.0 - 0.5 * s)
            angles.push_back(degreesBetween(glm::dvec3(p.normal[i]), x));
    }
    ASSERT_GT(angles.size(), 1000u);
    std::sort(angles.begin(), angles.end());
    EXPECT_LT(angles[angles.size() / 2], 8.0);
    EXPECT_LT(angles[angles.size() * 95 / 100], 16.0);
    EXPECT_LT(angles.back(), 25.0);
}

// A random ball has no facets; its surface normals scatter with the noise of the positions.
TEST(Normals, RandomBallSurfaceNormalsPointOutward) {
    const SceneParticles sp = builtWithNormals(sceneWith({ballBody(20000, Lattice::Random)}));
    const ParticleSet& p = sp.particles;
    const double s = latticeSpacing(ballBody(20000, Lattice::Random));
    std::vector<double> angles;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const glm::dvec3 x(p.position[i]);
        if (glm::length(x) > 1.0 - 0.5 * s)
            angles.push_back(degreesBetween(glm::dvec3(p.normal[i]), x));
    }
    // Measured: median 22.5 degrees. The random positions make the surface bumpy on the
    // scale of s, and the particle normals follow the bumps.
    std::sort(angles.begin(), angles.end());
    EXPECT_LT(angles[angles.size() / 2], 30.0);
}

// Interior particles of a lattice have a cancelling gradient: they fall back to the radial
// direction from the body centre, also far from the origin where float positions are coarse.
TEST(Normals, InteriorFallsBackToRadial) {
    for (const glm::dvec3 center : {glm::dvec3(3.0, -1.0, 2.0), glm::dvec3(700.0, 0.0, -300.0)}) {
        BodyDesc b = ballBody(20000);
        b.center = center;
        const SceneParticles sp = builtWithNormals(sceneWith({b}));
        const ParticleSet& p = sp.particles;
        int interior = 0, radial = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const glm::dvec3 r = glm::dvec3(p.position[i]) - b.center;
            if (glm::length(r) > 0.5 || glm::length(r) < 0.05) continue;
            ++interior;
            // 0.01 degrees: the normal is stored as float.
            radial += degreesBetween(glm::dvec3(p.normal[i]), r) < 0.01;
        }
        EXPECT_GT(interior, 1000);
        EXPECT_EQ(radial, interior) << "centre " << center.x;
    }
}

// The grid search finds exactly the neighbours a brute-force sum finds, also with smoothing
// lengths spanning several octaves (several grid levels) and bodies far apart.
TEST(Normals, GridMatchesBruteForce) {
    SplitMix64 rng(5);
    ParticleSet set;
    const std::size_t n = 1500;
    set.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double far = i % 3 == 0 ? 40.0 : 0.0;  // a second cluster far away
        set.position[i] = glm::vec3(glm::dvec3(rng.uniform() + far, rng.uniform(), rng.uniform()));
        set.h[i] = static_cast<float>(0.03 * std::pow(2.0, 4.0 * rng.uniform()));  // 0.03..0.48
        set.volume[i] =
            static_cast<float>(maxParticleVolume(double(set.h[i])) * (0.5 + rng.uniform()));
        set.body[i] = 0;
    }
    BodyInfo body;
    body.end = n;
    deriveNormals(set, std::span<const BodyInfo>(&body, 1));
    int compared = 0;
    for (std::size_t i = 0; i < n; ++i) {
        glm::dvec3 grad(0.0);
        double magnitude = 0.0;
        for (std::size_t j = 0; j < n; ++j) {
            const glm::dvec3 d = glm::dvec3(set.position[i]) - glm::dvec3(set.position[j]);
            const double r = glm::length(d);
            const double h = set.h[j];
            if (r == 0.0 || r >= 2.0 * h) continue;
            const double dW = set.volume[j] * m4KernelDerivative(r, h);
            grad += dW / r * d;
            magnitude += std::abs(dW);
        }
        if (glm::length(grad) < 1e-3 * magnitude) continue;  // nearly cancelling: ill-posed
        ++compared;
        EXPECT_LT(degreesBetween(glm::dvec3(set.normal[i]), -grad), 0.01) << i;
    }
    EXPECT_GT(compared, 1000);
}

// Gradient against the brute-force sum, Hessian against central differences of the gradient,
// at points between particles of uneven h (several grid levels).
TEST(FieldDerivatives, MatchBruteForceAndFiniteDifferences) {
    SplitMix64 rng(9);
    ParticleSet set;
    const std::size_t n = 800;
    set.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        set.position[i] = glm::vec3(glm::dvec3(rng.uniform(), rng.uniform(), rng.uniform()));
        set.h[i] = static_cast<float>(0.05 * std::pow(2.0, 2.0 * rng.uniform()));  // 0.05..0.2
        set.volume[i] = static_cast<float>(maxParticleVolume(double(set.h[i])));
    }
    auto bruteGradient = [&](const glm::dvec3& p) {
        glm::dvec3 g(0.0);
        for (std::size_t j = 0; j < n; ++j) {
            const glm::dvec3 d = p - glm::dvec3(set.position[j]);
            const double r = glm::length(d);
            if (r == 0.0 || r >= 2.0 * set.h[j]) continue;
            g += set.volume[j] * m4KernelDerivative(r, double(set.h[j])) / r * d;
        }
        return g;
    };
    std::vector<glm::dvec3> points;
    for (int k = 0; k < 40; ++k)
        points.emplace_back(0.2 + 0.6 * rng.uniform(), 0.2 + 0.6 * rng.uniform(),
                            0.2 + 0.6 * rng.uniform());
    const std::vector<FieldDerivatives> d = colourFieldDerivatives(set, points);
    ASSERT_EQ(d.size(), points.size());
    const double e = 1e-5;
    for (std::size_t k = 0; k < points.size(); ++k) {
        const glm::dvec3 g = bruteGradient(points[k]);
        EXPECT_LT(glm::length(d[k].gradient - g), 1e-5 * glm::length(g) + 1e-9) << k;
        double scale = 0.0;
        for (int a = 0; a < 3; ++a) scale = std::max(scale, glm::length(d[k].hessian[a]));
        for (int a = 0; a < 3; ++a) {
            glm::dvec3 step(0.0);
            step[a] = e;
            const glm::dvec3 column =
                (bruteGradient(points[k] + step) - bruteGradient(points[k] - step)) / (2.0 * e);
            EXPECT_LT(glm::length(d[k].hessian[a] - column), 1e-3 * scale) << k << " " << a;
        }
    }
}

TEST(Normals, SameResultOnAnyThreadCount) {
    const Scene scene = sceneWith({ballBody(30000, Lattice::Random)});
    SceneParticles one, many;
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        one = builtWithNormals(scene);
    }
    many = builtWithNormals(scene);
    ASSERT_EQ(one.particles.size(), many.particles.size());
    EXPECT_TRUE(std::equal(one.particles.normal.begin(), one.particles.normal.end(),
                           many.particles.normal.begin()));
    EXPECT_TRUE(
        std::equal(one.particles.uv.begin(), one.particles.uv.end(), many.particles.uv.begin()));
}

// ---- blackbody ---------------------------------------------------------------------------

TEST(Blackbody, LuminanceIsOneAt1500Kelvin) {
    EXPECT_NEAR(luminance(blackbodyRadiance(1500.0)), 1.0, 1e-5);
}

TEST(Blackbody, NegligibleBelow800Kelvin) {
    EXPECT_LT(luminance(blackbodyRadiance(800.0)), 1e-3);
    EXPECT_LT(luminance(blackbodyRadiance(500.0)), 1e-9);
    EXPECT_EQ(blackbodyRadiance(0.0), glm::vec3(0.0f));
    EXPECT_EQ(blackbodyRadiance(-10.0), glm::vec3(0.0f));
}

TEST(Blackbody, BluerAndBrighterWhenHotter) {
    double lastRatio = -1.0, lastY = 0.0;
    for (double t = 1500.0; t <= 12000.0; t += 500.0) {
        const glm::vec3 c = blackbodyRadiance(t);
        ASSERT_GT(c.r, 0.0f);
        const double ratio = c.b / c.r;
        EXPECT_GT(ratio, lastRatio) << t;
        EXPECT_GT(luminance(c), lastY) << t;
        lastRatio = ratio;
        lastY = luminance(c);
    }
}

// A ~6500 K blackbody is close to the D65 white of sRGB (its CCT is 6504 K but it lies off the
// daylight locus): R, G, B within 10 % of each other.
TEST(Blackbody, NearWhiteAt6500Kelvin) {
    const glm::vec3 c = blackbodyRadiance(6504.0);
    const float lo = std::min({c.r, c.g, c.b}), hi = std::max({c.r, c.g, c.b});
    EXPECT_LT(hi / lo, 1.10f);
}

// ---- buildParticles ----------------------------------------------------------------------

TEST(BuildParticles, BodiesRangesMaterialsGlowAndBounds) {
    BodyDesc planet = ballBody(5000);
    planet.name = "planet";
    planet.materialIndex = 1;
    planet.temperature = 2000.0;
    BodyDesc ring;
    ring.name = "ring";
    ring.shape = Shape::Ring;
    ring.center = glm::dvec3(0.5, 0.0, 0.0);
    ring.normal = glm::dvec3(0.1, 0.0, 1.0);
    ring.innerRadius = 1.6;
    ring.outerRadius = 2.4;
    ring.thickness = 0.04;
    ring.particles = 3000;
    ring.lattice = Lattice::Random;
    ring.materialIndex = 0;
    const SceneParticles sp = builtWithNormals(sceneWith({planet, ring}));
    const ParticleSet& p = sp.particles;
    ASSERT_EQ(sp.bodies.size(), 2u);
    EXPECT_EQ(sp.bodies[0].name, "planet");
    EXPECT_EQ(sp.bodies[1].name, "ring");
    EXPECT_EQ(sp.bodies[0].begin, 0u);
    EXPECT_EQ(sp.bodies[0].end, sp.bodies[1].begin);
    EXPECT_EQ(sp.bodies[1].end, p.size());
    EXPECT_EQ(sp.bodies[1].center, ring.center);
    EXPECT_NEAR(glm::length(sp.bodies[1].frame[2] - glm::normalize(ring.normal)), 0.0, 1e-12);
    EXPECT_NEAR(sp.bodies[0].meanH, 1.3 * latticeSpacing(planet), 1e-9);
    EXPECT_EQ(sp.bodies[1].material, 0u);

    const glm::vec3 hot = blackbodyRadiance(2000.0);
    for (std::size_t b = 0; b < 2; ++b) {
        for (std::size_t i = sp.bodies[b].begin; i < sp.bodies[b].end; ++i) {
            ASSERT_EQ(p.body[i], b);
            ASSERT_EQ(p.material[i], b == 0 ? 1u : 0u);
            ASSERT_EQ(p.glow[i], b == 0 ? hot : glm::vec3(0.0f));
            ASSERT_NEAR(glm::length(p.normal[i]), 1.0f, 1e-5f);
            ASSERT_GT(p.h[i], 0.0f);
            ASSERT_GT(p.volume[i], 0.0f);
            ASSERT_LE(p.volume[i], maxParticleVolume(p.h[i]) * (1 + 1e-6));
            for (int k = 0; k < 3; ++k) {
                ASSERT_LE(sp.boundsMin[k], p.position[i][k] - 2.0 * p.h[i] + 1e-6);
                ASSERT_GE(sp.boundsMax[k], p.position[i][k] + 2.0 * p.h[i] - 1e-6);
            }
        }
    }
    // The bounds are tight: some particle's support touches each face.
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (std::size_t i = 0; i < p.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], double(p.position[i][k]) - 2.0 * p.h[i]);
            hi[k] = std::max(hi[k], double(p.position[i][k]) + 2.0 * p.h[i]);
        }
    EXPECT_NEAR(glm::length(lo - sp.boundsMin), 0.0, 1e-9);
    EXPECT_NEAR(glm::length(hi - sp.boundsMax), 0.0, 1e-9);
}

TEST(BuildParticles, FileBody) {
    const auto dir = twinrender::testing::freshDir("derived_test");
    const auto path = dir / "two_bodies.csv";
    {
        std::ofstream f(path);
        f << "x,y,z,h,m,rho,u,v,temperature,body\n";
        // body 3: two particles with masses 1 and 3; body 1: one particle.
        f << "0,0,0,1,1,2,0.5,0.5,1500,3\n";
        f << "4,0,0,1,3,2,1.25,0.5,0,3\n";
        f << "0,10,0,2,1,1000,0.1,0.2,0,1\n";
    }
    BodyDesc b;
    b.name = "impact";
    b.shape = Shape::File;
    b.path = path;
    b.scale = 0.5;
    b.center = glm::dvec3(1, 2, 3);
    b.materialIndex = 2;
    b.temperature = 900.0;  // overridden by the file's column
    const SceneParticles sp = builtWithNormals(sceneWith({b}));
    const ParticleSet& p = sp.particles;
    ASSERT_EQ(p.size(), 3u);
    ASSERT_EQ(sp.bodies.size(), 2u);
    // Bodies in ascending order of the file's body value; file order kept within each.
    EXPECT_EQ(sp.bodies[0].name, "impact.1");
    EXPECT_EQ(sp.bodies[1].name, "impact.3");
    EXPECT_EQ(p.position[0], glm::vec3(1, 7, 3));
    EXPECT_EQ(p.position[1], glm::vec3(1, 2, 3));
    EXPECT_EQ(p.position[2], glm::vec3(3, 2, 3));
    EXPECT_EQ(p.h[0], 1.0f);
    EXPECT_EQ(p.h[1], 0.5f);
    // Volume: min(m / rho * scale^3, cap(h)).
    EXPECT_FLOAT_EQ(p.volume[0], 1.0f / 1000.0f * 0.125f);
    EXPECT_FLOAT_EQ(p.volume[1], static_cast<float>(maxParticleVolume(0.5)));
    // Centre of mass of body 3: (1 * 1 + 3 * 3) / 4 = 2.5 in x.
    EXPECT_NEAR(sp.bodies[1].center.x, 2.5, 1e-12);
    EXPECT_EQ(sp.bodies[1].meanH, 0.5);
    // uv from the file (u wrapped), temperature from the file.
    EXPECT_EQ(p.uv[1], glm::vec2(0.5f, 0.5f));
    EXPECT_NEAR(p.uv[2].x, 0.25f, 1e-6f);
    EXPECT_EQ(p.temperature[1], 1500.0f);
    EXPECT_EQ(p.temperature[2], 0.0f);
    EXPECT_EQ(p.glow[1], blackbodyRadiance(1500.0));
    EXPECT_EQ(p.material[0], 2u);
    std::filesystem::remove_all(dir);
}

// Values a file's doubles hold but the float particles do not are rejected at load, naming
// the file, the particle and the value: positions beyond 3.4e38, h that would round to 0 or
// to a denormal (whose kernel terms 1 / h^4 overflow), and either after the body's scale.
TEST(BuildParticles, FileValuesBeyondTheFloatRangeAreRejected) {
    const auto dir = twinrender::testing::freshDir("beyond_float");
    struct Case {
        std::string rows;
        double scale;
        std::string message;
    };
    const Case cases[] = {
        {"0,0,0,1\n-1e39,0,0,1\n", 1.0, "particle 1: position (-1e+39, 0, 0) is beyond"},
        {"0,0,0,1\n0,0,0,1e-300\n", 1.0, "particle 1: smoothing length h = 1e-300 is outside"},
        {"0,0,0,1e-39\n", 1.0, "particle 0: smoothing length h = 1e-39 is outside"},
        {"0,0,0,1e39\n", 1.0, "particle 0: smoothing length h = 1e+39 is outside"},
        {"1e30,0,0,1\n", 1e10, "particle 0: position (1e+40, 0, 0) after the body's scale"},
        {"0,0,0,1e-30\n", 1e-10, "particle 0: smoothing length h = 1"},
    };
    for (const Case& c : cases) {
        const auto path = dir / "values.csv";
        std::ofstream(path) << "x,y,z,h\n" << c.rows;
        BodyDesc b;
        b.name = "cloud";
        b.shape = Shape::File;
        b.path = path;
        b.scale = c.scale;
        try {
            builtWithNormals(sceneWith({b}));
            ADD_FAILURE() << "no error for " << c.rows;
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()).rfind(path.string() + ": particle ", 0), 0u)
                << e.what();
            EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
        }
    }
    std::filesystem::remove_all(dir);
}

// The real OpenSPH output (data/opensph_ball/): one body, volumes m/rho capped.
TEST(BuildParticles, OpenSphBall) {
    const std::filesystem::path path =
        ::twinrender::core::sourceDir() / "data" / "opensph_ball" / "ball.ssf";
    ASSERT_TRUE(std::filesystem::exists(path)) << path << " is missing";
    BodyDesc b;
    b.name = "ball";
    b.shape = Shape::File;
    b.path = path;
    b.scale = 1e-3;  // m -> km
    const SceneParticles sp = builtWithNormals(sceneWith({b}));
    const ParticleSet& p = sp.particles;
    ASSERT_EQ(p.size(), 10648u);
    ASSERT_EQ(sp.bodies.size(), 1u);
    EXPECT_EQ(sp.bodies[0].name, "ball");
    EXPECT_LT(glm::length(sp.bodies[0].center), 1e-3);
    EXPECT_NEAR(sp.bodies[0].meanH, 0.097, 0.005);  // h ~ 97 m
    double rMax = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        ASSERT_LE(p.volume[i], maxParticleVolume(p.h[i]) * (1 + 1e-6));
        rMax = std::max(rMax, double(glm::length(p.position[i])));
    }
    EXPECT_NEAR(rMax, 1.0, 0.05);  // radius 1 km
    // Surface normals: measured median 5.8, 95th percentile 13 degrees (a lattice, as above).
    std::vector<double> angles;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (glm::length(p.position[i]) > rMax - 0.05)
            angles.push_back(degreesBetween(glm::dvec3(p.normal[i]), glm::dvec3(p.position[i])));
    std::sort(angles.begin(), angles.end());
    EXPECT_LT(angles[angles.size() / 2], 8.0);
    EXPECT_LT(angles[angles.size() * 95 / 100], 16.0);
}

// Per-particle temperatures (a file column) each get their own glow.
TEST(Glow, PerParticleTemperatures) {
    ParticleSet set;
    set.resize(5000);
    for (std::size_t i = 0; i < set.size(); ++i) set.temperature[i] = 500.0f + float(i);
    deriveGlow(set);
    for (std::size_t i = 0; i < set.size(); i += 97)
        EXPECT_EQ(set.glow[i], blackbodyRadiance(set.temperature[i]));
}

}  // namespace
}  // namespace twinrender::core
