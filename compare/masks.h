// The masks of docs/design.md ("Metrics"): the per-buffer metrics are taken only where they mean
// something. Every mask is derived from the two AOV images (core/frame.h) alone, pixel by pixel:
//  - covered: A > 0.5 (the coverage channel; partial coverage at an anti-aliased edge counts
//    when the surface fills more than half the pixel);
//  - covered in both: covered in the reference and in the test;
//  - same body: covered in both and the same body id in both;
//  - interior: same-body pixels whose disc of radius r (pixels, Euclidean) holds only pixels of
//    that same body in both images: away from silhouettes (either image's) and from the
//    boundaries between bodies, where the screen-space blur and the pixel footprint make the
//    buffers disagree by construction. The image edge is not a silhouette: pixels of the disc
//    that fall outside the image are ignored;
//  - facing the light: covered in both and N.L > 0 in the reference (the reference normal
//    against the direction toward the light). Where the light is unknown, every pixel covered
//    in both.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "core/image.h"

namespace twinrender::compare {

// A pixel is covered when its A channel exceeds this (docs/design.md: A is 1 where hit).
constexpr float COVERED_ALPHA = 0.5f;

// A binary image: 1 inside, 0 outside, one byte a pixel, row-major like core::Image
// (pixel p = y * width + x).
class Mask {
  public:
    Mask() = default;
    // All pixels outside.
    Mask(int width, int height)
        : mWidth(width), mHeight(height), mValues(static_cast<std::size_t>(width) * height, 0) {}

    int width() const { return mWidth; }
    int height() const { return mHeight; }
    std::size_t pixelCount() const { return mValues.size(); }

    bool operator()(int x, int y) const { return mValues[index(x, y)] != 0; }
    bool operator[](std::size_t p) const { return mValues[p] != 0; }
    void set(int x, int y, bool inside) { mValues[index(x, y)] = inside ? 1 : 0; }
    void set(std::size_t p, bool inside) { mValues[p] = inside ? 1 : 0; }

    // Number of pixels inside.
    std::size_t count() const;
    // One channel `channel`, 1 inside and 0 outside (for reports and debugging).
    core::Image toImage(const std::string& channel) const;

    bool operator==(const Mask& other) const = default;

  private:
    std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * mWidth + x; }

    int mWidth = 0;
    int mHeight = 0;
    std::vector<std::uint8_t> mValues;
};

struct MaskSettings {
    // Radius of the interior erosion, pixels, >= 0 (0: interior = same body). 2 skips the
    // one-pixel anti-aliased rim and the pixel the screen-space blur mixes across an edge.
    int interiorRadius = 2;
    // Whether lightDirection is known. Without it, "facing the light" is every pixel covered
    // in both.
    bool hasLight = false;
    // The way the light travels (core::LightSettings::direction, the scene's light.direction),
    // world space, any length > 0. A surface faces the light when N . (-lightDirection) > 0.
    glm::dvec3 lightDirection{0.0, 0.0, -1.0};
};

// Every mask of a pair, all of the same size as the images.
struct Masks {
    Mask referenceCovered;
    Mask testCovered;
    Mask coveredInBoth;
    Mask sameBody;
    Mask interior;
    Mask facingLight;
};

// A > COVERED_ALPHA. Throws core::NotComparableError when the image has no channel A.
Mask coveredMask(const core::Image& image);

// Covered in both and the same id in both (ids compared as stored, exact below 2^24).
Mask sameBodyMask(const core::Image& reference, const core::Image& test, const Mask& coveredInBoth);

// The pixels of `sameBody` whose disc of radius `radius` (|offset| <= radius, offsets outside
// the image ignored) holds only pixels of `sameBody` with the reference id of the centre.
// Throws std::invalid_argument for a negative radius.
Mask interiorMask(const core::Image& reference, const Mask& sameBody, int radius);

// Pixels of `coveredInBoth` whose reference normal (N.X, N.Y, N.Z) has a positive dot product
// with -lightDirection; all of `coveredInBoth` when !settings.hasLight.
Mask facingLightMask(const core::Image& reference, const Mask& coveredInBoth,
                     const MaskSettings& settings);

// All masks of a pair of AOV images, from the channels they carry: without id in both, same
// body is covered in both; without the reference's id, interior is same body; without the
// reference's normals, facing the light is covered in both. Throws core::NotComparableError when
// the sizes differ (naming both) or either image lacks A; std::invalid_argument for a negative
// interiorRadius or a zero light direction.
Masks computeMasks(const core::Image& reference, const core::Image& test,
                   const MaskSettings& settings = {});

}  // namespace twinrender::compare
