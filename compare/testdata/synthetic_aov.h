// A small AOV image made without any renderer, for the metric tests and the synthetic report
// (report/testdata/synthetic_report.h).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/frame.h"
#include "core/image.h"

namespace twinrender::compare::testdata {

// A sphere of radius `radius` (pixels) centred at (cx, cy), seen along -z, lit from the upper
// left; its left half is body 0, its right half body 1; the lower right quarter is shadowed; an
// emitter far to the right casts the irradiance 2 max(n.x, 0) (not added to the beauty); its
// atmosphere scatters 0.05 (0.1 blue) over the disc's outer ring (0.9 < r^2 < 1; not added).
inline core::Image syntheticAov(int width, int height, double cx, double cy, double radius) {
    core::Image img = core::aov::makeImage(width, height);
    auto ch = [&](const char* name) { return img.channelIndex(name); };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double dx = (x + 0.5 - cx) / radius, dy = (y + 0.5 - cy) / radius;
            const double r2 = dx * dx + dy * dy;
            if (r2 >= 1.0) continue;
            const double nz = std::sqrt(1.0 - r2);
            const double nx = dx, ny = -dy;
            const bool shadowed = dx > 0.2 && dy > 0.2;
            const double lambert = std::max(0.0, (-0.5 * nx + 0.5 * ny + 0.707 * nz));
            const double lit = shadowed ? 0.0 : 1.0;
            const int body = dx < 0.0 ? 0 : 1;
            const double albedo[2][3] = {{0.8, 0.5, 0.3}, {0.3, 0.6, 0.9}};
            for (int c = 0; c < 3; ++c)
                img.at(x, y, c) = static_cast<float>(albedo[body][c] * (0.05 + lit * lambert));
            img.at(x, y, ch("A")) = 1.0f;
            img.at(x, y, ch("Z")) = static_cast<float>(10.0 - 3.0 * nz);
            img.at(x, y, ch("N.X")) = static_cast<float>(nx);
            img.at(x, y, ch("N.Y")) = static_cast<float>(ny);
            img.at(x, y, ch("N.Z")) = static_cast<float>(nz);
            img.at(x, y, ch("uv.U")) = static_cast<float>(0.5 + std::atan2(nx, nz) / 6.2831853);
            img.at(x, y, ch("uv.V")) = static_cast<float>(0.5 + 0.5 * ny);
            img.at(x, y, ch("id")) = static_cast<float>(body);
            img.at(x, y, ch("emission.R")) = r2 > 0.8 ? 0.6f : 0.0f;
            img.at(x, y, ch("emission.G")) = r2 > 0.8 ? 0.2f : 0.0f;
            img.at(x, y, ch("shadow")) = static_cast<float>(lit);
            for (const char* c : {"irradiance.R", "irradiance.G", "irradiance.B"})
                img.at(x, y, ch(c)) = static_cast<float>(2.0 * std::max(nx, 0.0));
            if (r2 > 0.9) {
                img.at(x, y, ch("inscatter.R")) = img.at(x, y, ch("inscatter.G")) = 0.05f;
                img.at(x, y, ch("inscatter.B")) = 0.1f;
            }
        }
    return img;
}

}  // namespace twinrender::compare::testdata
