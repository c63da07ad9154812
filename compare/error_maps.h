// The per-pixel error maps of compare::computeMetrics (MetricResult::errorMaps) as the
// colour-mapped images a scene page shows beside the two renders.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/image.h"

namespace twinrender::compare {

// A colour-mapped error image and the range its colours span.
struct ErrorMapImage {
    std::string path;   // PNG, relative to the scene folder
    std::string label;  // "ꟻLIP error", "normal error"
    double lo = 0.0;    // value at the dark end of the colour map
    double hi = 1.0;    // value at the bright end
    std::string unit;   // "" for unitless, "°", "px"
};

// How one error map is shown: under which buffer of the page, and over which fixed range, so
// that colours mean the same in every scene and run.
struct ErrorMapStyle {
    std::string_view key;  // MetricResult::errorMaps key: "beauty.flip", "normal", ...
    // The page's buffer it is shown under: "beauty", "normal", ...; BUFFER.NAME for a second
    // map of BUFFER, shown beside its first ("beauty.hdrflip" beside the ꟻLIP map).
    std::string_view buffer;
    std::string_view label;
    double lo = 0.0, hi = 1.0;
    std::string_view unit;
};

// The style of every error map computeMetrics writes.
const std::vector<ErrorMapStyle>& errorMapStyles();

// Writes every map as DIR/<stem>.<buffer>.png through magma (colour_map.h) over its style's
// range; a map without a style under its own key, over 0..its maximum. Returns buffer ->
// ErrorMapImage ("beauty.flip" becomes "beauty", "beauty.hdrflip" stays), ready for
// SceneReport::errorMaps.
std::map<std::string, ErrorMapImage> writeErrorMapImages(
    const std::map<std::string, core::Image>& errorMaps, const std::filesystem::path& dir,
    const std::string& stem = "error");

}  // namespace twinrender::compare
