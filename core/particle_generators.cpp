#include "core/particle_generators.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <stdexcept>

#include "core/error.h"
#include "core/sph_kernel.h"

namespace twinrender::core {

namespace {

constexpr double PI = std::numbers::pi;
constexpr std::int64_t MAX_PARTICLES = std::int64_t(1) << 31;

// Cube root by Newton's method on plain IEEE arithmetic, so the spacing (and everything that
// follows from it) is the same on every platform; std::cbrt is not required to be correctly
// rounded. x > 0 and finite.
double portableCbrt(double x) {
    int e = 0;
    const double m = std::frexp(x, &e);  // x = m 2^e, m in [0.5, 1), exact
    int e3 = e / 3;
    int r = e - 3 * e3;
    if (r < 0) {
        r += 3;
        e3 -= 1;
    }
    const double a = std::ldexp(m, r);  // in [0.5, 4), x = a 2^(3 e3)
    double y = 0.6 + 0.35 * a;          // within 25 % of cbrt(a) on [0.5, 4)
    for (int i = 0; i < 8; ++i) y -= (y * y * y - a) / (3.0 * y * y);
    return std::ldexp(y, e3);
}

bool finite3(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The shape in body-local coordinates: points whose (cylindrical or spherical) radius squared
// lies in [rIn2, rOut2] and, for the ring, |z| <= zHalf.
struct LocalShape {
    double rIn2 = 0.0;
    double rOut2 = 0.0;
    bool cylindrical = false;  // ring: radius in the xy plane
    double zHalf = 0.0;        // ring: half thickness
    glm::dvec3 extent{0.0};    // half extents of the bounding box
    double thickness = 0.0;    // wall / ring thickness, 0 for a ball

    bool contains(const glm::dvec3& p) const {
        if (cylindrical && std::abs(p.z) > zHalf) return false;
        const double q = p.x * p.x + p.y * p.y + (cylindrical ? 0.0 : p.z * p.z);
        return q >= rIn2 && q <= rOut2;
    }

    // The x intervals of the line (y, z) inside the shape; returns how many (0, 1 or 2).
    int xIntervals(double y, double z, double (&a)[2], double (&b)[2]) const {
        if (cylindrical && std::abs(z) > zHalf) return 0;
        const double q = y * y + (cylindrical ? 0.0 : z * z);
        const double outer2 = rOut2 - q;
        if (outer2 < 0.0) return 0;
        const double outer = std::sqrt(outer2);
        const double inner2 = rIn2 - q;
        if (inner2 <= 0.0) {
            a[0] = -outer;
            b[0] = outer;
            return 1;
        }
        const double inner = std::sqrt(inner2);
        a[0] = -outer;
        b[0] = -inner;
        a[1] = inner;
        b[1] = outer;
        return 2;
    }
};

[[noreturn]] void invalidBody(const BodyDesc& body, const std::string& what) {
    throw InputError(fmt::format("{}: body '{}': {}", body.where.empty() ? "scene" : body.where,
                                 body.name, what));
}

LocalShape localShape(const BodyDesc& body) {
    if (!finite3(body.center)) invalidBody(body, "center must be finite");
    auto positive = [&](double v, const char* key) {
        if (!(std::isfinite(v) && v > 0.0))
            invalidBody(body, fmt::format("{} must be a positive number (got {})", key, v));
    };
    LocalShape s;
    switch (body.shape) {
        case Shape::Ball:
            positive(body.radius, "radius");
            s.rOut2 = body.radius * body.radius;
            s.extent = glm::dvec3(body.radius);
            break;
        case Shape::Shell: {
            positive(body.radius, "radius");
            positive(body.thickness, "thickness");
            if (body.thickness > body.radius)
                invalidBody(body, fmt::format("thickness {} exceeds the radius {} (use shape = "
                                              "\"ball\" for a full ball)",
                                              body.thickness, body.radius));
            const double rIn = body.radius - body.thickness;
            s.rIn2 = rIn * rIn;
            s.rOut2 = body.radius * body.radius;
            s.extent = glm::dvec3(body.radius);
            s.thickness = body.thickness;
            break;
        }
        case Shape::Ring:
            positive(body.outerRadius, "outer_radius");
            positive(body.thickness, "thickness");
            if (!(std::isfinite(body.innerRadius) && body.innerRadius >= 0.0 &&
                  body.innerRadius < body.outerRadius))
                invalidBody(body, fmt::format("inner_radius must be in [0, outer_radius = {}) "
                                              "(got {})",
                                              body.outerRadius, body.innerRadius));
            s.rIn2 = body.innerRadius * body.innerRadius;
            s.rOut2 = body.outerRadius * body.outerRadius;
            s.cylindrical = true;
            s.zHalf = 0.5 * body.thickness;
            s.extent = glm::dvec3(body.outerRadius, body.outerRadius, s.zHalf);
            s.thickness = body.thickness;
            break;
        case Shape::File:
            invalidBody(body, "shape = \"file\" has no generator (it is read from its path)");
    }
    return s;
}

double localVolume(const BodyDesc& body) {
    switch (body.shape) {
        case Shape::Ball:
            return 4.0 / 3.0 * PI * body.radius * body.radius * body.radius;
        case Shape::Shell: {
            const double rIn = body.radius - body.thickness;
            return 4.0 / 3.0 * PI * (body.radius * body.radius * body.radius - rIn * rIn * rIn);
        }
        case Shape::Ring:
            return PI *
                   (body.outerRadius * body.outerRadius - body.innerRadius * body.innerRadius) *
                   body.thickness;
        case Shape::File:
            break;
    }
    return 0.0;
}

// Layer spacing / s of the lattice's layers along the pole axis.
double layerSpacingFactor(Lattice lattice) {
    // hcp: d sqrt(2/3) with d = 2^(1/6) s.
    return lattice == Lattice::Hcp ? 1.1224620483093730 * 0.81649658092772603 : 1.0;
}

// Lattice geometry: points x = x0(j, k) + i dx on rows y(j, k), layers z(k).
struct LatticeGeometry {
    double dx = 0.0;
    double dy = 0.0;  // row spacing
    double dz = 0.0;  // layer spacing
    bool hcp = false;
    double d = 0.0;        // hcp nearest-neighbour distance
    double zOffset = 0.5;  // layer k at (k + zOffset) dz: 1/2 puts the mid-plane between layers

    double layerZ(std::int64_t k) const { return (static_cast<double>(k) + zOffset) * dz; }
    double rowY(std::int64_t j, std::int64_t k) const {
        // hcp B layers sit over the triangle centres of the A layer: shift (d/2, d sqrt(3)/6).
        const double shift = hcp && (k & 1) ? d * (std::numbers::sqrt3 / 6.0) : 0.0;
        return hcp ? static_cast<double>(j) * dy + shift : (static_cast<double>(j) + 0.5) * dy;
    }
    double rowX0(std::int64_t j, std::int64_t k) const {
        if (!hcp) return 0.5 * dx;
        return static_cast<double>((j & 1) + (k & 1)) * (0.5 * d);
    }
};

LatticeGeometry latticeGeometry(Lattice lattice, double s) {
    LatticeGeometry g;
    if (lattice == Lattice::Hcp) {
        // hcp: each site owns d^3 / sqrt(2) of volume; set that to s^3.
        constexpr double TWO_POW_SIXTH = 1.1224620483093730;  // 2^(1/6)
        g.hcp = true;
        g.d = TWO_POW_SIXTH * s;
        g.dx = g.d;
        g.dy = g.d * (std::numbers::sqrt3 / 2.0);
        g.dz = s * layerSpacingFactor(lattice);  // d sqrt(2/3)
    } else {
        g.dx = g.dy = g.dz = s;
    }
    return g;
}

void checkCount(const BodyDesc& body, double count) {
    if (!(count < static_cast<double>(MAX_PARTICLES)))
        invalidBody(body, fmt::format("the shape would need {:.3g} particles (at most {}); "
                                      "lower 'particles' or thicken the shape",
                                      count, MAX_PARTICLES));
}

void generateLattice(const BodyDesc& body, const LocalShape& shape, const LatticeGeometry& g,
                     const glm::dmat3& frame, std::vector<glm::vec3>& out) {
    const std::int64_t kMin = static_cast<std::int64_t>(std::floor(-shape.extent.z / g.dz)) - 1;
    const std::int64_t kMax = static_cast<std::int64_t>(std::ceil(shape.extent.z / g.dz)) + 1;
    const std::int64_t jMin = static_cast<std::int64_t>(std::floor(-shape.extent.y / g.dy)) - 2;
    const std::int64_t jMax = static_cast<std::int64_t>(std::ceil(shape.extent.y / g.dy)) + 2;
    double a[2], b[2];
    for (std::int64_t k = kMin; k <= kMax; ++k) {
        const double z = g.layerZ(k);
        for (std::int64_t j = jMin; j <= jMax; ++j) {
            const double y = g.rowY(j, k);
            const double x0 = g.rowX0(j, k);
            const int n = shape.xIntervals(y, z, a, b);
            for (int t = 0; t < n; ++t) {
                const auto iMin = static_cast<std::int64_t>(std::ceil((a[t] - x0) / g.dx)) - 1;
                const auto iMax = static_cast<std::int64_t>(std::floor((b[t] - x0) / g.dx)) + 1;
                for (std::int64_t i = iMin; i <= iMax; ++i) {
                    const glm::dvec3 local(x0 + static_cast<double>(i) * g.dx, y, z);
                    // The intervals come from sqrt; the exact test decides boundary points
                    // (and drops the one-cell margin added above).
                    if (!shape.contains(local)) continue;
                    out.emplace_back(body.center + frame * local);
                }
            }
        }
    }
}

void generateRandom(const BodyDesc& body, const LocalShape& shape, std::int64_t count,
                    const glm::dmat3& frame, std::vector<glm::vec3>& out) {
    SplitMix64 rng(body.seed);
    out.reserve(static_cast<std::size_t>(count));
    while (static_cast<std::int64_t>(out.size()) < count) {
        const double x = (2.0 * rng.uniform() - 1.0) * shape.extent.x;
        const double y = (2.0 * rng.uniform() - 1.0) * shape.extent.y;
        const double z = (2.0 * rng.uniform() - 1.0) * shape.extent.z;
        const glm::dvec3 local(x, y, z);
        if (shape.contains(local)) out.emplace_back(body.center + frame * local);
    }
}

}  // namespace

glm::dmat3 bodyFrame(const glm::dvec3& pole) {
    const double len = glm::length(pole);
    if (!(std::isfinite(len) && len > 0.0))
        throw std::invalid_argument(
            fmt::format("pole axis ({}, {}, {}) is zero or not finite", pole.x, pole.y, pole.z));
    const glm::dvec3 z = pole / len;
    // World x made orthogonal to z; world y when z is close to x (|z.x| >= 0.9, ~25 degrees).
    const glm::dvec3 seed = std::abs(z.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 x = glm::normalize(seed - glm::dot(seed, z) * z);
    const glm::dvec3 y = glm::cross(z, x);
    return glm::dmat3(x, y, z);
}

double shapeVolume(const BodyDesc& body) {
    localShape(body);  // validates
    return localVolume(body);
}

double latticeSpacing(const BodyDesc& body) {
    localShape(body);  // validates
    if (body.particles < 1)
        invalidBody(body, fmt::format("particles must be at least 1 (got {})", body.particles));
    const double s0 = portableCbrt(localVolume(body) / static_cast<double>(body.particles));
    switch (body.shape) {
        case Shape::Shell:
            // At least two layers across the wall (see the header).
            return std::min(s0, 0.5 * body.thickness);
        case Shape::Ring: {
            // A whole number n >= 2 of layers fills the thickness (see the header).
            const double kz = layerSpacingFactor(body.lattice);
            const double layers = std::max(2.0, std::round(body.thickness / (kz * s0)));
            return body.thickness / (layers * kz);
        }
        default:
            return s0;
    }
}

double expectedParticles(const BodyDesc& body) {
    const double s = latticeSpacing(body);
    return localVolume(body) / (s * s * s);
}

bool insideShape(const BodyDesc& body, const glm::dvec3& local) {
    return localShape(body).contains(local);
}

GeneratedBody generateBody(const BodyDesc& body) {
    const LocalShape shape = localShape(body);
    GeneratedBody out;
    out.spacing = latticeSpacing(body);
    if (body.smoothing) {
        if (!(std::isfinite(*body.smoothing) && *body.smoothing > 0.0))
            invalidBody(
                body, fmt::format("smoothing must be a positive number (got {})", *body.smoothing));
        out.h = *body.smoothing;
    } else {
        out.h = 1.3 * out.spacing;
    }
    const double s3 = out.spacing * out.spacing * out.spacing;
    out.volume = std::min(s3, maxParticleVolume(out.h));

    glm::dmat3 frame;
    try {
        frame = bodyFrame(body.normal);
    } catch (const std::invalid_argument& e) {
        invalidBody(body, fmt::format("normal: {}", e.what()));
    }

    const double expected = expectedParticles(body);
    checkCount(body, expected);
    if (body.lattice == Lattice::Random) {
        const auto count = std::max<std::int64_t>(1, std::llround(expected));
        generateRandom(body, shape, count, frame, out.position);
    } else {
        // The bounding box holds every candidate; reserve for the expected count plus margin.
        out.position.reserve(static_cast<std::size_t>(expected * 1.1) + 64);
        LatticeGeometry geometry = latticeGeometry(body.lattice, out.spacing);
        if (body.shape == Shape::Ring) {
            // n layers fill the thickness exactly: centred on the mid-plane, a layer on it
            // when n is odd.
            const auto layers = std::llround(body.thickness / geometry.dz);
            geometry.zOffset = layers % 2 ? 0.0 : 0.5;
        }
        generateLattice(body, shape, geometry, frame, out.position);
        if (out.position.empty()) {
            // A shape smaller than one lattice cell: keep one particle in the middle of the
            // material (the centre of a ball, mid-wall on the local x axis otherwise) rather
            // than an empty body.
            const double r = 0.5 * (std::sqrt(shape.rIn2) + std::sqrt(shape.rOut2));
            const glm::dvec3 local(body.shape == Shape::Ball ? 0.0 : r, 0.0, 0.0);
            out.position.emplace_back(body.center + frame * local);
        }
    }
    return out;
}

}  // namespace twinrender::core
