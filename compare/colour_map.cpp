#include "compare/colour_map.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "core/image_io.h"

namespace twinrender::compare {

namespace fs = std::filesystem;

namespace {

// Every 16th of magma's 256 entries and the last; linear interpolation between them stays
// within 0.5 % of the full table.
constexpr std::array<std::array<float, 3>, 17> MAGMA = {{
    {0.001462f, 0.000466f, 0.013866f},
    {0.039608f, 0.031090f, 0.133515f},
    {0.113094f, 0.065492f, 0.276784f},
    {0.211718f, 0.061992f, 0.418647f},
    {0.316654f, 0.071690f, 0.485380f},
    {0.414709f, 0.110431f, 0.504662f},
    {0.512831f, 0.148179f, 0.507648f},
    {0.613617f, 0.181811f, 0.498536f},
    {0.716387f, 0.214982f, 0.475290f},
    {0.816914f, 0.255895f, 0.436461f},
    {0.904281f, 0.319610f, 0.388137f},
    {0.960949f, 0.418323f, 0.359630f},
    {0.986700f, 0.535582f, 0.382210f},
    {0.996096f, 0.653659f, 0.446213f},
    {0.996898f, 0.769591f, 0.534892f},
    {0.992440f, 0.884330f, 0.640099f},
    {0.987053f, 0.991438f, 0.749504f},
}};

// Table index i sits at t = 16 i / 255, the last at t = 1.
double magmaKnot(std::size_t i) {
    return i + 1 < MAGMA.size() ? 16.0 * i / 255.0 : 1.0;
}

}  // namespace

void magma(double t, float rgb[3]) {
    t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
    std::size_t i = 0;
    while (i + 2 < MAGMA.size() && t > magmaKnot(i + 1)) ++i;
    const double a = magmaKnot(i), b = magmaKnot(i + 1);
    const double f = std::clamp((t - a) / (b - a), 0.0, 1.0);
    for (int c = 0; c < 3; ++c)
        rgb[c] = static_cast<float>(MAGMA[i][c] + f * (MAGMA[i + 1][c] - MAGMA[i][c]));
}

core::Image colourMapped(const core::Image& map, int channel, double lo, double hi) {
    if (channel < 0 || channel >= map.channelCount())
        throw std::invalid_argument(fmt::format("colourMapped: no channel {}", channel));
    core::Image out(map.width(), map.height(), {"R", "G", "B"});
    const double span = hi > lo ? hi - lo : 1.0;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, map.pixelCount(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& pixels) {
                          for (std::size_t p = pixels.begin(); p != pixels.end(); ++p) {
                              const float v = map.at(p, channel);
                              float rgb[3] = {0.0f, 0.0f, 0.0f};
                              if (!std::isnan(v)) magma((v - lo) / span, rgb);
                              for (int c = 0; c < 3; ++c) out.at(p, c) = rgb[c];
                          }
                      });
    return out;
}

void writeErrorMapPng(const core::Image& map, int channel, double lo, double hi,
                      const fs::path& png) {
    core::writeImage(colourMapped(map, channel, lo, hi), png);
}

std::string magmaCssGradient() {
    std::string g = "linear-gradient(to right";
    for (int i = 0; i <= 16; ++i) {
        float rgb[3];
        magma(i / 16.0, rgb);
        g += fmt::format(", rgb({},{},{}) {:.2f}%", static_cast<int>(std::lround(255 * rgb[0])),
                         static_cast<int>(std::lround(255 * rgb[1])),
                         static_cast<int>(std::lround(255 * rgb[2])), 100.0 * i / 16.0);
    }
    return g + ")";
}

}  // namespace twinrender::compare
