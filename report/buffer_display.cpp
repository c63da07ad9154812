#include "report/buffer_display.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/vec3.hpp>
#include <limits>
#include <stdexcept>

#include "core/image_io.h"
#include "core/shading.h"
#include "core/write_roots.h"

namespace twinrender::report {

namespace fs = std::filesystem;

const std::vector<std::string>& bufferNames() {
    static const std::vector<std::string> names = {"beauty",     "normal",   "uv", "depth",
                                                   "id",         "shadow",   "ao", "emission",
                                                   "irradiance", "inscatter"};
    return names;
}

namespace {

// Background of every buffer but beauty: a dark slate, darker than any depth or shadow grey.
constexpr float BACKGROUND[3] = {0.10f, 0.11f, 0.13f};

void hsvToRgb(double h, double s, double v, float rgb[3]) {
    const double hh = (h - std::floor(h)) * 6.0;
    const int i = static_cast<int>(hh) % 6;
    const double f = hh - std::floor(hh);
    const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    double r = v, g = t, b = p;
    switch (i) {
        case 0:
            r = v;
            g = t;
            b = p;
            break;
        case 1:
            r = q;
            g = v;
            b = p;
            break;
        case 2:
            r = p;
            g = v;
            b = t;
            break;
        case 3:
            r = p;
            g = q;
            b = v;
            break;
        case 4:
            r = t;
            g = p;
            b = v;
            break;
        default:
            r = v;
            g = p;
            b = q;
            break;
    }
    rgb[0] = static_cast<float>(r);
    rgb[1] = static_cast<float>(g);
    rgb[2] = static_cast<float>(b);
}

float clamp01(float v) {
    return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
}

std::vector<std::string> channelsOf(std::string_view buffer) {
    if (buffer == "beauty") return {"R", "G", "B"};
    if (buffer == "normal") return {"N.X", "N.Y", "N.Z"};
    if (buffer == "uv") return {"uv.U", "uv.V"};
    if (buffer == "depth") return {"Z"};
    if (buffer == "id") return {"id"};
    if (buffer == "shadow") return {"shadow"};
    if (buffer == "ao") return {"ao"};
    if (buffer == "emission") return {"emission.R", "emission.G", "emission.B"};
    if (buffer == "irradiance") return {"irradiance.R", "irradiance.G", "irradiance.B"};
    if (buffer == "inscatter") return {"inscatter.R", "inscatter.G", "inscatter.B"};
    throw std::invalid_argument(
        fmt::format("unknown buffer '{}'; buffers are beauty, normal, "
                    "uv, depth, id, shadow, ao, emission, irradiance, inscatter",
                    buffer));
}

bool anyNonZero(const core::Image& aov, const std::vector<std::string>& channels) {
    for (const std::string& name : channels) {
        const int c = aov.channelIndex(name);
        for (std::size_t p = 0; p < aov.pixelCount(); ++p)
            if (aov.at(p, c) != 0.0f) return true;
    }
    return false;
}

}  // namespace

std::pair<double, double> depthRange(const core::Image& a, const core::Image& b) {
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const core::Image* image : {&a, &b}) {
        const int z = image->channelIndex("Z");
        if (z < 0) continue;
        const int cov = image->channelIndex("A");
        for (std::size_t p = 0; p < image->pixelCount(); ++p) {
            const float d = image->at(p, z);
            if (!(d > 0.0f) || !std::isfinite(d) || (cov >= 0 && !(image->at(p, cov) > 0.0f)))
                continue;
            lo = std::min(lo, static_cast<double>(d));
            hi = std::max(hi, static_cast<double>(d));
        }
    }
    if (!(hi > 0.0)) return {0.0, 0.0};
    return {lo, hi};
}

core::Image visualiseBuffer(const core::Image& aov, std::string_view buffer,
                            const BufferVisualSettings& settings) {
    const std::vector<std::string> names = channelsOf(buffer);
    std::vector<int> ch;
    for (const auto& n : names) ch.push_back(aov.requireChannel(n));
    const int cov = aov.channelIndex("A");
    const int zc = aov.channelIndex("Z");
    auto covered = [&](std::size_t p) {
        if (cov >= 0) return aov.at(p, cov) > 0.0f;
        if (zc >= 0) return std::isfinite(aov.at(p, zc));
        return true;
    };
    std::pair<double, double> range = settings.depthRange;
    if (buffer == "depth" && !(range.first > 0.0 && range.second >= range.first))
        range = depthRange(aov, aov);
    const double logSpan = range.second > range.first && range.first > 0.0
                               ? std::log(range.second / range.first)
                               : 0.0;

    core::Image out(aov.width(), aov.height(), {"R", "G", "B"});
    for (std::size_t p = 0; p < aov.pixelCount(); ++p) {
        float rgb[3] = {BACKGROUND[0], BACKGROUND[1], BACKGROUND[2]};
        if (buffer == "beauty") {
            const glm::vec3 c = core::tonemap(
                glm::vec3(aov.at(p, ch[0]), aov.at(p, ch[1]), aov.at(p, ch[2])), settings.exposure);
            rgb[0] = c.r, rgb[1] = c.g, rgb[2] = c.b;
        } else if (covered(p)) {
            if (buffer == "normal") {
                for (int c = 0; c < 3; ++c) rgb[c] = clamp01(0.5f + 0.5f * aov.at(p, ch[c]));
            } else if (buffer == "uv") {
                rgb[0] = clamp01(aov.at(p, ch[0]));
                rgb[1] = clamp01(aov.at(p, ch[1]));
                rgb[2] = 0.0f;
            } else if (buffer == "depth") {
                const double z = aov.at(p, ch[0]);
                if (std::isfinite(z) && z > 0.0) {
                    // Near is white, far a dark grey (0.25), log-scaled: equal depth ratios get
                    // equal steps, as a log depth buffer spends its precision.
                    const double t = logSpan > 0.0
                                         ? std::clamp(std::log(z / range.first) / logSpan, 0.0, 1.0)
                                         : 0.0;
                    rgb[0] = rgb[1] = rgb[2] = static_cast<float>(1.0 - 0.75 * t);
                }
            } else if (buffer == "id") {
                const float id = aov.at(p, ch[0]);
                if (id >= 0.0f && std::isfinite(id)) {
                    // Golden-ratio hue steps: neighbouring ids get distant hues; the colour
                    // depends on the id only, so both renders colour a body alike.
                    const double k = std::round(id);
                    hsvToRgb(0.08 + 0.6180339887498949 * k, 0.62, 0.95, rgb);
                }
            } else if (buffer == "shadow" || buffer == "ao") {
                rgb[0] = rgb[1] = rgb[2] = 0.3f + 0.7f * clamp01(aov.at(p, ch[0]));
            } else if (buffer == "emission" || buffer == "inscatter") {
                const glm::vec3 c =
                    core::tonemap(glm::vec3(aov.at(p, ch[0]), aov.at(p, ch[1]), aov.at(p, ch[2])),
                                  settings.exposure);
                rgb[0] = c.r, rgb[1] = c.g, rgb[2] = c.b;
            } else if (buffer == "irradiance") {
                // As the radiance a white Lambertian surface reflects of it, E / pi.
                const glm::vec3 e(aov.at(p, ch[0]), aov.at(p, ch[1]), aov.at(p, ch[2]));
                const glm::vec3 c = core::tonemap(e * float(1.0 / M_PI), settings.exposure);
                rgb[0] = c.r, rgb[1] = c.g, rgb[2] = c.b;
            }
        }
        for (int c = 0; c < 3; ++c) out.at(p, c) = rgb[c];
    }
    return out;
}

std::map<std::string, std::string> writeBufferImages(const core::Image& aov,
                                                     const core::Image* beautyDisplay,
                                                     const fs::path& dir, const std::string& stem,
                                                     const BufferVisualSettings& settings) {
    core::makeFolders(dir);
    std::map<std::string, std::string> written;
    for (const std::string& buffer : bufferNames()) {
        const std::string name = stem + "." + buffer + ".png";
        if (buffer == "beauty" && beautyDisplay) {
            const std::vector<std::string> rgb = {"R", "G", "B"};
            core::writeImage(beautyDisplay->select(rgb), dir / name);
            written[buffer] = name;
            continue;
        }
        bool has = true;
        for (const auto& c : channelsOf(buffer)) has = has && aov.hasChannel(c);
        if (!has) continue;
        // The light of emitting surfaces only where the scene casts it (light.emissive_light).
        // The in-scatter only where a body has an atmosphere.
        if ((buffer == "irradiance" || buffer == "inscatter") &&
            !anyNonZero(aov, channelsOf(buffer)))
            continue;
        core::writeImage(visualiseBuffer(aov, buffer, settings), dir / name);
        written[buffer] = name;
    }
    return written;
}

}  // namespace twinrender::report
