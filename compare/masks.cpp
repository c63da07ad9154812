#include "compare/masks.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "compare/distance_transform.h"
#include "compare/image_pair.h"
#include "core/error.h"

namespace twinrender::compare {

std::size_t Mask::count() const {
    return static_cast<std::size_t>(std::count(mValues.begin(), mValues.end(), std::uint8_t{1}));
}

core::Image Mask::toImage(const std::string& channel) const {
    core::Image image(mWidth, mHeight, {channel});
    for (std::size_t p = 0; p < mValues.size(); ++p) image.at(p, 0) = mValues[p] ? 1.0f : 0.0f;
    return image;
}

namespace {

// Calls f(p) for every pixel, rows in parallel.
template <typename F>
void forEachPixel(int width, int height, F&& f) {
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y) {
            const std::size_t row = static_cast<std::size_t>(y) * width;
            for (int x = 0; x < width; ++x) f(row + x);
        }
    });
}

void requireMaskSize(const core::Image& image, const Mask& mask, const char* what) {
    if (image.width() != mask.width() || image.height() != mask.height())
        throw std::invalid_argument(fmt::format("masks: the {} mask is {}x{} but the image {}x{}",
                                                what, mask.width(), mask.height(), image.width(),
                                                image.height()));
}

}  // namespace

Mask coveredMask(const core::Image& image) {
    const int a = image.requireChannel("A");
    Mask mask(image.width(), image.height());
    forEachPixel(image.width(), image.height(),
                 [&](std::size_t p) { mask.set(p, image.at(p, a) > COVERED_ALPHA); });
    return mask;
}

Mask sameBodyMask(const core::Image& reference, const core::Image& test,
                  const Mask& coveredInBoth) {
    requireSameSize("masks", reference, test);
    requireMaskSize(reference, coveredInBoth, "covered-in-both");
    const int refId = reference.requireChannel("id");
    const int testId = test.requireChannel("id");
    Mask mask(reference.width(), reference.height());
    forEachPixel(reference.width(), reference.height(), [&](std::size_t p) {
        mask.set(p, coveredInBoth[p] && reference.at(p, refId) == test.at(p, testId));
    });
    return mask;
}

Mask interiorMask(const core::Image& reference, const Mask& sameBody, int radius) {
    if (radius < 0)
        throw std::invalid_argument(
            fmt::format("masks: the interior radius must be >= 0 pixels, got {}", radius));
    requireMaskSize(reference, sameBody, "same-body");
    if (radius == 0) return sameBody;
    const int w = reference.width();
    const int h = reference.height();
    const int idC = reference.requireChannel("id");
    // Two pixels carry the same label when both are same-body pixels of one id, or both are not
    // same-body pixels.
    auto sameLabel = [&](std::size_t p, std::size_t q) {
        return sameBody[p] == sameBody[q] &&
               (!sameBody[p] || reference.at(p, idC) == reference.at(q, idC));
    };

    // Label boundaries: pixels with a 4-neighbour of another label. The different-label pixel
    // nearest to a pixel p is on a boundary (the pixel one step from it toward p is nearer to p,
    // so carries p's label), hence a pixel farther than `radius` from every boundary pixel is
    // interior; only the band within `radius` of a boundary needs its disc checked.
    Mask boundary(w, h);
    forEachPixel(w, h, [&](std::size_t p) {
        const int x = static_cast<int>(p % w);
        const int y = static_cast<int>(p / w);
        const bool edge = (x > 0 && !sameLabel(p, p - 1)) || (x + 1 < w && !sameLabel(p, p + 1)) ||
                          (y > 0 && !sameLabel(p, p - w)) || (y + 1 < h && !sameLabel(p, p + w));
        boundary.set(p, edge);
    });
    const std::vector<float> d2 = squaredDistanceTransform(boundary);

    std::vector<std::pair<int, int>> disc;
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx)
            if (dx * dx + dy * dy <= radius * radius) disc.emplace_back(dx, dy);
    const float r2 = static_cast<float>(radius) * static_cast<float>(radius);

    Mask interior(w, h);
    forEachPixel(w, h, [&](std::size_t p) {
        if (!sameBody[p]) return;
        if (d2[p] > r2) {
            interior.set(p, true);
            return;
        }
        const int x = static_cast<int>(p % w);
        const int y = static_cast<int>(p / w);
        for (const auto& [dx, dy] : disc) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;  // the image edge is no outline
            if (!sameLabel(p, static_cast<std::size_t>(qy) * w + qx)) return;
        }
        interior.set(p, true);
    });
    return interior;
}

Mask facingLightMask(const core::Image& reference, const Mask& coveredInBoth,
                     const MaskSettings& settings) {
    requireMaskSize(reference, coveredInBoth, "covered-in-both");
    if (!settings.hasLight) return coveredInBoth;
    const glm::dvec3 toLight = -settings.lightDirection;
    if (!(toLight.x != 0.0 || toLight.y != 0.0 || toLight.z != 0.0))
        throw std::invalid_argument("masks: the light direction is the zero vector");
    const int nx = reference.requireChannel("N.X");
    const int ny = reference.requireChannel("N.Y");
    const int nz = reference.requireChannel("N.Z");
    Mask mask(reference.width(), reference.height());
    forEachPixel(reference.width(), reference.height(), [&](std::size_t p) {
        if (!coveredInBoth[p]) return;
        const double nl = reference.at(p, nx) * toLight.x + reference.at(p, ny) * toLight.y +
                          reference.at(p, nz) * toLight.z;
        mask.set(p, nl > 0.0);
    });
    return mask;
}

Masks computeMasks(const core::Image& reference, const core::Image& test,
                   const MaskSettings& settings) {
    requireSameSize("masks", reference, test);
    Masks m;
    m.referenceCovered = coveredMask(reference);
    m.testCovered = coveredMask(test);
    m.coveredInBoth = Mask(reference.width(), reference.height());
    for (std::size_t p = 0; p < m.coveredInBoth.pixelCount(); ++p)
        m.coveredInBoth.set(p, m.referenceCovered[p] && m.testCovered[p]);
    // From what the images carry (a test image may carry only some AOV channels): without id
    // in both, same body is covered in both; without the reference's id, the interior is not
    // eroded; without its normals, facing the light is covered in both.
    const bool ids = reference.hasChannel("id") && test.hasChannel("id");
    m.sameBody = ids ? sameBodyMask(reference, test, m.coveredInBoth) : m.coveredInBoth;
    m.interior = reference.hasChannel("id")
                     ? interiorMask(reference, m.sameBody, settings.interiorRadius)
                     : m.sameBody;
    MaskSettings facing = settings;
    facing.hasLight = settings.hasLight && reference.hasChannel("N.X");
    m.facingLight = facingLightMask(reference, m.coveredInBoth, facing);
    return m;
}

}  // namespace twinrender::compare
