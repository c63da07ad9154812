#include "core/texture.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/common.hpp>

#include "core/error.h"
#include "core/image_io.h"
#include "core/shading.h"

namespace twinrender::core {

namespace {

constexpr int PROCEDURAL_WIDTH = 1024;  // texels around the equator
constexpr int PROCEDURAL_HEIGHT = 512;  // texels pole to pole

std::uint32_t hash2(int x, int y, std::uint32_t seed) {
    std::uint32_t h = static_cast<std::uint32_t>(x) * 0x8da6b343u ^
                      static_cast<std::uint32_t>(y) * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return h;
}

// Value noise on a lattice of `cells` x `cells/2` cells, periodic in u, smooth (C1) inside.
float valueNoise(float u, float v, int cells, std::uint32_t seed) {
    const int cu = cells, cv = std::max(cells / 2, 1);
    const float x = u * cu, y = v * cv;
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    const float fx = x - x0, fy = y - y0;
    auto lattice = [&](int i, int j) {
        i = ((i % cu) + cu) % cu;
        j = std::clamp(j, 0, cv);
        return (hash2(i, j, seed) & 0xffffff) / float(0xffffff);
    };
    const float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
    const float a = lattice(x0, y0) + (lattice(x0 + 1, y0) - lattice(x0, y0)) * sx;
    const float b = lattice(x0, y0 + 1) + (lattice(x0 + 1, y0 + 1) - lattice(x0, y0 + 1)) * sx;
    return a + (b - a) * sy;
}

// Fractal value noise in [0, 1].
float fbm(float u, float v, std::uint32_t seed) {
    float sum = 0, amp = 0.5f, norm = 0;
    for (int octave = 0, cells = 8; octave < 5; ++octave, cells *= 2, amp *= 0.5f) {
        sum += amp * valueNoise(u, v, cells, seed + octave);
        norm += amp;
    }
    return sum / norm;
}

bool isLand(float u, float v) {
    return fbm(u, v, 7) > 0.52f;
}

glm::vec3 proceduralTexel(const std::string& name, float u, float v) {
    if (name == "none") return glm::vec3(0.0f);
    if (name == "latlong_grid") {
        // Lines every 15 degrees; one texel is 360/1024 degrees wide.
        const float lon = u * 360.0f, lat = v * 180.0f;
        const float dLon = std::abs(lon - 15.0f * std::round(lon / 15.0f));
        const float dLat = std::abs(lat - 15.0f * std::round(lat / 15.0f));
        if (u < 2.0f / PROCEDURAL_WIDTH || u > 1.0f - 2.0f / PROCEDURAL_WIDTH)
            return {0.8f, 0.05f, 0.05f};  // the seam meridian, so seam errors show
        if (dLon < 0.9f || dLat < 0.9f) return glm::vec3(0.05f);
        // Alternate two greys per 30-degree band so uv shifts are visible between lines.
        const bool odd = (int(lon / 30.0f) + int(lat / 30.0f)) % 2;
        return odd ? glm::vec3(0.55f, 0.55f, 0.6f) : glm::vec3(0.75f, 0.72f, 0.65f);
    }
    if (name == "checker") {
        const bool odd = (int(u * 16.0f) + int(v * 8.0f)) % 2;
        return odd ? glm::vec3(0.2f) : glm::vec3(0.7f);
    }
    if (name == "continents") {
        if (isLand(u, v)) {
            const float n = fbm(u, v, 31);
            return glm::mix(glm::vec3(0.12f, 0.3f, 0.08f), glm::vec3(0.45f, 0.36f, 0.2f), n);
        }
        return {0.02f, 0.06f, 0.25f};
    }
    if (name == "city_lights") {
        if (!isLand(u, v)) return glm::vec3(0.0f);
        const float n = valueNoise(u, v, 256, 99);
        return n > 0.8f ? glm::vec3(1.0f, 0.75f, 0.4f) * (n - 0.8f) * 5.0f : glm::vec3(0.0f);
    }
    if (name == "lava") {
        const float n = fbm(u, v, 55);
        const float crack = std::clamp(1.0f - std::abs(n - 0.5f) * 12.0f, 0.0f, 1.0f);
        return glm::vec3(4.0f, 1.2f, 0.2f) * crack;
    }
    throw std::out_of_range(name);
}

}  // namespace

Texture::Texture(Image rgb) : mImage(std::move(rgb)) {}

Texture Texture::load(const TextureSource& source) {
    switch (source.kind) {
        case TextureSource::Kind::Constant: {
            Image img(1, 1, {"R", "G", "B"});
            for (int c = 0; c < 3; ++c) img.at(0, 0, c) = static_cast<float>(source.value[c]);
            return Texture(std::move(img));
        }
        case TextureSource::Kind::Procedural: {
            Image img(PROCEDURAL_WIDTH, PROCEDURAL_HEIGHT, {"R", "G", "B"});
            try {
                for (int y = 0; y < PROCEDURAL_HEIGHT; ++y)
                    for (int x = 0; x < PROCEDURAL_WIDTH; ++x) {
                        // Row 0 is v = 1 (north), as images are stored top row first.
                        const float u = (x + 0.5f) / PROCEDURAL_WIDTH;
                        const float v = 1.0f - (y + 0.5f) / PROCEDURAL_HEIGHT;
                        const glm::vec3 c = proceduralTexel(source.procedural, u, v);
                        for (int k = 0; k < 3; ++k) img.at(x, y, k) = c[k];
                    }
            } catch (const std::out_of_range&) {
                throw InputError(
                    fmt::format("{}: unknown procedural '{}'; use none, latlong_grid, "
                                "checker, continents, city_lights or lava",
                                source.where, source.procedural));
            }
            return Texture(std::move(img));
        }
        case TextureSource::Kind::File: {
            Image in;
            try {
                in = readImage(source.path);
            } catch (const InputError& e) {
                throw InputError(fmt::format("{}: {}", source.where, e.what()));
            }
            const bool isFloat =
                source.path.extension() == ".exr" || source.path.extension() == ".hdr";
            Image img(in.width(), in.height(), {"R", "G", "B"});
            const int r = in.channelIndex("R");
            const int g = in.channelIndex("G") >= 0 ? in.channelIndex("G") : r;
            const int b = in.channelIndex("B") >= 0 ? in.channelIndex("B") : r;
            if (r < 0)
                throw InputError(
                    fmt::format("{}: {} has no R channel", source.where, source.path.string()));
            for (std::size_t p = 0; p < in.pixelCount(); ++p) {
                const float rgb[3] = {in.at(p, r), in.at(p, g), in.at(p, b)};
                for (int c = 0; c < 3; ++c) img.at(p, c) = isFloat ? rgb[c] : srgbToLinear(rgb[c]);
            }
            return Texture(std::move(img));
        }
    }
    return {};
}

glm::vec3 Texture::sample(glm::vec2 uv) const {
    const int w = mImage.width(), h = mImage.height();
    if (w == 1 && h == 1) return {mImage.at(0, 0, 0), mImage.at(0, 0, 1), mImage.at(0, 0, 2)};
    // Texel centres at (i + 0.5)/w; u repeats, v clamps to the edge texels (GL semantics).
    // Image row 0 holds v = 1.
    const float x = uv.x * w - 0.5f;
    const float y = (1.0f - uv.y) * h - 0.5f;
    const float fx0 = std::floor(x), fy0 = std::floor(y);
    const float tx = x - fx0, ty = y - fy0;
    int x0 = static_cast<int>(fx0) % w;
    if (x0 < 0) x0 += w;
    const int x1 = (x0 + 1) % w;
    const int y0 = std::clamp(static_cast<int>(fy0), 0, h - 1);
    const int y1 = std::clamp(static_cast<int>(fy0) + 1, 0, h - 1);
    glm::vec3 out;
    for (int c = 0; c < 3; ++c) {
        const float a = mImage.at(x0, y0, c) + (mImage.at(x1, y0, c) - mImage.at(x0, y0, c)) * tx;
        const float b = mImage.at(x0, y1, c) + (mImage.at(x1, y1, c) - mImage.at(x0, y1, c)) * tx;
        out[c] = a + (b - a) * ty;
    }
    return out;
}

std::vector<Material> loadMaterials(const Scene& scene) {
    std::vector<Material> out;
    for (const auto& m : scene.materials) {
        Material mat;
        mat.name = m.name;
        mat.diffuse = Texture::load(m.diffuse);
        mat.specular = Texture::load(m.specular);
        mat.emission = Texture::load(m.emission);
        mat.cityLights = Texture::load(m.cityLights);
        mat.shininess = static_cast<float>(m.shininess);
        out.push_back(std::move(mat));
    }
    return out;
}

}  // namespace twinrender::core
