#include "compare/contact_band.h"

#include <cmath>
#include <stdexcept>

#include "compare/buffer_metrics.h"

namespace twinrender::compare {

Mask contactBandMask(const core::Image& reference, const Masks& masks, int radius) {
    if (radius < 1) throw std::invalid_argument("contact band: radius must be >= 1 pixel");
    const int w = reference.width(), h = reference.height();
    const int cId = reference.requireChannel("id");
    Mask band(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!masks.sameBody(x, y)) continue;
            const float id = reference.at(x, y, cId);
            bool near = false;
            for (int dy = -radius; dy <= radius && !near; ++dy)
                for (int dx = -radius; dx <= radius && !near; ++dx) {
                    const int qx = x + dx, qy = y + dy;
                    if (dx * dx + dy * dy > radius * radius || qx < 0 || qy < 0 || qx >= w ||
                        qy >= h)
                        continue;
                    near = masks.referenceCovered(qx, qy) && reference.at(qx, qy, cId) != id;
                }
            band.set(x, y, near);
        }
    return band;
}

ContactBandResult contactBandError(const core::Image& reference, const core::Image& test,
                                   const Masks& masks, int radius) {
    const Mask band = contactBandMask(reference, masks, radius);
    const int ru = reference.requireChannel("uv.U"), rv = reference.requireChannel("uv.V");
    const int tu = test.requireChannel("uv.U"), tv = test.requireChannel("uv.V");
    int re[3], te[3];
    const char* names[3] = {"emission.R", "emission.G", "emission.B"};
    for (int c = 0; c < 3; ++c) {
        re[c] = reference.requireChannel(names[c]);
        te[c] = test.requireChannel(names[c]);
    }
    double uvSum = 0.0, eSum = 0.0;
    ContactBandResult r;
    for (std::size_t p = 0; p < band.pixelCount(); ++p) {
        if (!band[p]) continue;
        ++r.pixels;
        uvSum +=
            uvDistance(reference.at(p, ru), reference.at(p, rv), test.at(p, tu), test.at(p, tv));
        for (int c = 0; c < 3; ++c) {
            const double d = double(test.at(p, te[c])) - reference.at(p, re[c]);
            eSum += d * d;
        }
    }
    r.uvMean = r.pixels ? uvSum / double(r.pixels) : NAN;
    r.emissionRmse = r.pixels ? std::sqrt(eSum / (3.0 * double(r.pixels))) : NAN;
    return r;
}

}  // namespace twinrender::compare
