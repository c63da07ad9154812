#include "compare/error_maps.h"

#include <algorithm>
#include <cmath>

#include "compare/colour_map.h"

namespace twinrender::compare {

const std::vector<ErrorMapStyle>& errorMapStyles() {
    // Ranges: where the colour map saturates, chosen so that a typical real-time error sits
    // mid-range: ꟻLIP is in [0, 1]; normals beyond 30 degrees are plainly wrong; 5 % depth
    // and 0.05 of uv are far beyond smoothing noise; shadow codes are 1 (false) and 2 (missed);
    // a quarter of the hemisphere is a plain occlusion error; an irradiance error of 1 is a
    // third of what a surface of radiance 1 casts on its own plane's neighbours (pi); an
    // in-scatter error of 0.1 is a tenth of a sky of radiance 1.
    static const std::vector<ErrorMapStyle> styles = {
        {"beauty.flip", "beauty", "ꟻLIP error", 0.0, 1.0, ""},
        {"beauty.hdrflip", "beauty.hdrflip", "HDR-ꟻLIP error", 0.0, 1.0, ""},
        {"normal", "normal", "normal error", 0.0, 30.0, "°"},
        {"uv", "uv", "uv error", 0.0, 0.05, ""},
        {"depth", "depth", "relative depth error", 0.0, 0.05, ""},
        {"id", "id", "visible body differs", 0.0, 1.0, ""},
        {"shadow", "shadow", "shadow: 1 false, 2 missed", 0.0, 2.0, ""},
        {"emission", "emission", "emission error", 0.0, 1.0, ""},
        {"ao", "ao", "ambient occlusion error", 0.0, 0.25, ""},
        {"irradiance", "irradiance", "irradiance error (luminance)", 0.0, 1.0, ""},
        {"inscatter", "inscatter", "in-scatter error (luminance)", 0.0, 0.1, ""},
    };
    return styles;
}

namespace {

// The largest finite value of channel 0; 1 when there is none above 0.
double ownMaximum(const core::Image& map) {
    double hi = 0.0;
    for (std::size_t p = 0; p < map.pixelCount(); ++p)
        if (std::isfinite(map.at(p, 0))) hi = std::max(hi, static_cast<double>(map.at(p, 0)));
    return hi > 0.0 ? hi : 1.0;
}

}  // namespace

std::map<std::string, ErrorMapImage> writeErrorMapImages(
    const std::map<std::string, core::Image>& errorMaps, const std::filesystem::path& dir,
    const std::string& stem) {
    std::map<std::string, ErrorMapImage> out;
    for (const auto& [key, map] : errorMaps) {
        if (map.channelCount() < 1 || map.pixelCount() == 0) continue;
        const auto& styles = errorMapStyles();
        const auto st = std::find_if(styles.begin(), styles.end(),
                                     [&k = key](const ErrorMapStyle& s) { return s.key == k; });
        const ErrorMapStyle style =
            st != styles.end() ? *st : ErrorMapStyle{key, key, "", 0.0, ownMaximum(map), ""};
        const std::string buffer(style.buffer);
        const std::string name = stem + "." + buffer + ".png";
        writeErrorMapPng(map, 0, style.lo, style.hi, dir / name);
        out[buffer] =
            ErrorMapImage{name, style.label.empty() ? key + " error" : std::string(style.label),
                          style.lo, style.hi, std::string(style.unit)};
    }
    return out;
}

}  // namespace twinrender::compare
