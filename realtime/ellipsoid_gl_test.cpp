// Ellipsoid impostors (realtime.particles.shape = "ellipsoid") on llvmpipe against the same
// ellipsoids (realtime/anisotropy.h) ray-cast on the CPU in double precision: the G-buffer's
// coverage, depth and normal, and the shadow map's outline.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <optional>

#include "core/camera.h"
#include "realtime/anisotropy.h"
#include "realtime/gl/context.h"
#include "realtime/impostor_radius.h"
#include "realtime/renderer.h"

namespace twinrender::realtime {
namespace {

constexpr float SPACING = 0.1f;
constexpr float H = 2.0f * SPACING;  // about 48 neighbours in a layer's 2 h: most flatten

// Square lattice layers of particles (cubic spacing SPACING, smoothing length H) seen from
// `eye`, towards the origin. The material is black: only geometry and shadows are checked.
struct LayerScene {
    core::Scene scene;
    core::SceneParticles particles;
    std::vector<core::Material> materials = std::vector<core::Material>(1);

    explicit LayerScene(const glm::dvec3& eye) {
        scene.camera.position = eye;
        scene.camera.width = 160;
        scene.camera.height = 90;
    }

    // n x n x layers particles of body `body`, centred on `centre`, the layers along the
    // rotation's z axis.
    void lattice(std::uint32_t body, int n, int layers, glm::dvec3 centre, glm::dmat3 rotation) {
        core::ParticleSet& ps = particles.particles;
        for (int z = 0; z < layers; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const glm::dvec3 local =
                        double(SPACING) * glm::dvec3(x - (n - 1) / 2.0, y - (n - 1) / 2.0, -z);
                    const std::size_t i = ps.size();
                    ps.resize(i + 1);
                    ps.position[i] = glm::vec3(centre + rotation * local);
                    ps.h[i] = H;
                    ps.volume[i] = SPACING * SPACING * SPACING;
                    ps.body[i] = body;
                    ps.material[i] = 0;
                    ps.normal[i] = glm::vec3(rotation[2]);
                }
        particles.bodies.resize(std::max<std::size_t>(particles.bodies.size(), body + 1));
        glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-lo);
        for (const glm::vec3& p : ps.position) {
            lo = glm::min(lo, glm::dvec3(p) - 2.0 * double(H));
            hi = glm::max(hi, glm::dvec3(p) + 2.0 * double(H));
        }
        particles.boundsMin = lo;
        particles.boundsMax = hi;
    }
};

// Fixed radii (0.9 h) and the impostors' own normals; no smoothing, bloom or shadows.
Settings ellipsoidSettings() {
    Settings s;
    ParticleSettings& p = s.particles;
    p.shape = ParticleShape::Ellipsoid;
    p.radius = RadiusModel::Fixed;
    p.normal = NormalModel::Sphere;
    s.shadows = ShadowMode::None;
    s.ssss.enabled = s.bloom.enabled = false;
    return s;
}

// A ray against particle i's ellipsoid, in its unit-sphere space.
struct RayHit {
    double t = std::numeric_limits<double>::infinity();  // nearest entry along the ray
    glm::dvec3 normal{0.0};                              // world, unit
    double miss2 =
        std::numeric_limits<double>::infinity();  // squared closest approach (1: grazing)
};

RayHit castAt(const core::ParticleSet& ps, const Ellipsoid& e, std::size_t i,
              const core::Ray& ray) {
    glm::dmat3 inverse;  // rows: axis_k / |axis_k|^2
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3 a(e.axes[k]);
        const glm::dvec3 row = a / glm::dot(a, a);
        for (int c = 0; c < 3; ++c) inverse[c][k] = row[c];
    }
    const glm::dvec3 o = inverse * (ray.origin - glm::dvec3(ps.position[i]) - glm::dvec3(e.shift));
    const glm::dvec3 m = inverse * ray.direction;
    const double a = glm::dot(m, m), b = glm::dot(o, m), c = glm::dot(o, o) - 1.0;
    RayHit hit;
    hit.miss2 = glm::dot(o, o) - b * b / a;
    const double disc = b * b - a * c;
    if (disc < 0.0) return hit;
    hit.t = (-b - std::sqrt(disc)) / a;
    if (hit.t < 0.0) hit.t = std::numeric_limits<double>::infinity();
    hit.normal = glm::normalize(glm::transpose(inverse) * (o + hit.t * m));
    return hit;
}

class EllipsoidTest : public ::testing::Test {
  protected:
    gl::Context context;
    Device device{context};

    core::Frame render(const LayerScene& t, const Settings& s) {
        return Renderer(device, s).render({t.scene, t.particles, t.materials});
    }
};

// A layer tilted by 35 degrees seen obliquely: in its interior ellipsoids flattened 4 : 4 : 1
// across the layer and lifted along its normal (anchor = "surface"), towards its edge also
// pulled inwards, and at the edge spheres (fewer than 25 neighbours). Every pixel agrees with
// the CPU ray cast: coverage, eye depth and the ellipsoid's normal.
TEST_F(EllipsoidTest, TheGBufferHoldsTheEllipsoids) {
    LayerScene t({0.4, -2.4, 1.6});
    const glm::dmat3 tilt =
        glm::dmat3(glm::rotate(glm::dmat4(1.0), glm::radians(35.0), glm::dvec3(1.0, 0.2, 0.0)));
    t.lattice(0, 11, 1, glm::dvec3(0.0), tilt);
    const Settings s = ellipsoidSettings();
    const core::ParticleSet& ps = t.particles.particles;
    const std::vector<Ellipsoid> ellipsoids =
        anisotropicEllipsoids(ps, fixedRadii(ps, s.particles.radiusScale), s.particles.anisotropy);
    int spheres = 0, shifted = 0;
    for (const Ellipsoid& e : ellipsoids) {
        spheres += e.isSphere();
        shifted += glm::length(e.shift) > 0.1f * SPACING;
    }
    EXPECT_GT(spheres, 10);
    EXPECT_GT(shifted, 10);

    const core::Frame r = render(t, s);
    const core::Image& image = r.image;
    const core::Camera camera(t.scene.camera);
    int covered = 0, compared = 0;
    double worstDepth = 0.0, worstNormal = 0.0;
    for (int y = 0; y < camera.height(); ++y)
        for (int x = 0; x < camera.width(); ++x) {
            const core::Ray ray = camera.ray(x + 0.5, y + 0.5);
            RayHit front, second;
            bool grazing = false;
            for (std::size_t i = 0; i < ps.size(); ++i) {
                const RayHit hit = castAt(ps, ellipsoids[i], i, ray);
                grazing = grazing || std::abs(hit.miss2 - 1.0) < 0.02;
                if (hit.t < front.t) {
                    second = front;
                    front = hit;
                } else if (hit.t < second.t) {
                    second = hit;
                }
            }
            // Outline pixels, within 1 % of an ellipsoid's silhouette, may go either way.
            if (grazing && (!std::isfinite(front.t) || front.t > second.t - 1e-3)) continue;
            const bool hit = std::isfinite(front.t);
            ASSERT_EQ(image.at(x, y, image.requireChannel("A")), hit ? 1.0f : 0.0f)
                << x << "," << y;
            if (!hit) continue;
            ++covered;
            const double z = camera.eyeDepth(ray.origin + front.t * ray.direction);
            const double depth = std::abs(image.at(x, y, image.requireChannel("Z")) - z) / z;
            worstDepth = std::max(worstDepth, depth);
            // Where two ellipsoids meet the depth is continuous, the normal is not.
            if (second.t - front.t < 1e-3 * front.t) continue;
            ++compared;
            const glm::dvec3 n(image.at(x, y, image.requireChannel("N.X")),
                               image.at(x, y, image.requireChannel("N.Y")),
                               image.at(x, y, image.requireChannel("N.Z")));
            worstNormal =
                std::max(worstNormal,
                         glm::degrees(std::acos(std::clamp(glm::dot(n, front.normal), -1.0, 1.0))));
        }
    EXPECT_GT(covered, 2000);
    EXPECT_GT(compared, 1000);
    // Float ray casting at a distance of about 20 ellipsoid radii (measured 1.4e-6 and 0.03
    // degrees).
    EXPECT_LT(worstDepth, 1e-5);
    EXPECT_LT(worstNormal, 0.1);
}

// The shadow pass draws the same ellipsoids: a layer 0.6 above a ground slab, the light
// straight down, casts the union of its ellipsoids' outlines onto the ground.
TEST_F(EllipsoidTest, TheShadowMapCastsTheEllipsoids) {
    LayerScene t({0.2, -1.9, 2.0});
    t.lattice(0, 13, 1, glm::dvec3(0.0, 0.0, 0.6), glm::dmat3(1.0));
    const std::size_t layer = t.particles.particles.size();
    t.lattice(1, 31, 2, glm::dvec3(0.0), glm::dmat3(1.0));
    t.scene.light.direction = {0.0, 0.0, -1.0};
    Settings s = ellipsoidSettings();
    s.shadows = ShadowMode::Map;
    const core::ParticleSet& ps = t.particles.particles;
    const std::vector<Ellipsoid> ellipsoids =
        anisotropicEllipsoids(ps, fixedRadii(ps, s.particles.radiusScale), s.particles.anisotropy);

    const core::Frame r = render(t, s);
    const core::Image& image = r.image;
    const core::Camera camera(t.scene.camera);
    int shadowed = 0, compared = 0, wrong = 0;
    for (int y = 0; y < camera.height(); ++y)
        for (int x = 0; x < camera.width(); ++x) {
            if (image.at(x, y, image.requireChannel("id")) != 1.0f) continue;
            const core::Ray ray = camera.ray(x + 0.5, y + 0.5);
            const double z = image.at(x, y, image.requireChannel("Z"));
            const glm::dvec3 ground =
                ray.origin + ray.direction * (z / glm::dot(ray.direction, camera.forward()));
            // Straight up towards the light, against the layer's ellipsoids.
            const core::Ray up{ground, {0.0, 0.0, 1.0}};
            bool blocked = false, grazing = false;
            for (std::size_t i = 0; i < layer; ++i) {
                const RayHit hit = castAt(ps, ellipsoids[i], i, up);
                blocked = blocked || std::isfinite(hit.t);
                grazing = grazing || std::abs(hit.miss2 - 1.0) < 0.03;
            }
            if (grazing) continue;
            ++compared;
            shadowed += blocked;
            wrong += image.at(x, y, image.requireChannel("shadow")) != (blocked ? 0.0f : 1.0f);
        }
    EXPECT_GT(compared, 3000);
    EXPECT_GT(shadowed, 400);
    EXPECT_EQ(wrong, 0);
}

}  // namespace
}  // namespace twinrender::realtime
