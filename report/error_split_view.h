// The error split (docs/design.md, "The error split") drawn small: where a scene's ꟻLIP comes
// from, the screen-space surface (surface.beauty.flip), the real-time light
// (lighting.beauty.flip) or the shading floor (shading.beauty.flip), as bars beside the whole
// image's beauty.flip on one scale. HTML and CSS only (report.css, .split-*).
#pragma once

#include <string>

#include "compare/thresholds.h"

namespace twinrender::report {

using compare::MetricValues;

// True when the metrics hold the split's parts.
bool hasErrorSplit(const MetricValues& metrics);

// The bars: `compact` for an index cell (the three parts, values in the tooltip), else the
// scene page's figure (the whole and the three parts, with their values and a caption).
// "" without the split.
std::string errorSplitBars(const MetricValues& metrics, bool compact);

}  // namespace twinrender::report
