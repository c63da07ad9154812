// The metrics of a sequence scene, from those of its frames (report.h SequenceFrame): what
// its thresholds, baseline and the run's summary see.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "report/report.h"

namespace twinrender::report {

using compare::MetricValues;

// Every metric of the frames' pairs at its worst frame (the largest of a lower-is-better
// metric, the smallest of a higher-is-better one, the farthest from its origin of a closer
// one), so a bound holds every frame to it; the times (time.<renderer>_ms) as the median
// frame; temporal.flicker and temporal.normal_flicker_deg as their mean and largest
// (temporal.flicker_mean, temporal.flicker_max, temporal.normal_flicker_mean_deg,
// temporal.normal_flicker_max_deg). The frames' other temporal.* values stay per frame.
// NaN values are left out; a metric NaN in every frame is NaN.
MetricValues summariseSequence(const std::vector<SequenceFrame>& frames);

// The temporal metrics summariseSequence pools over the frames, which a sequence has and a
// still scene lacks: temporal.flicker_mean, temporal.flicker_max,
// temporal.normal_flicker_mean_deg, temporal.normal_flicker_max_deg.
std::vector<std::string> pooledTemporalMetrics();

// The metrics that do not apply to any frame (SequenceFrame::notApplicable), with the first
// frame's reason; none for no frames.
std::map<std::string, std::string> notApplicableInEvery(const std::vector<SequenceFrame>& frames);

// The frame with the largest beauty.flip (the first frame when none has one); 0 for none.
std::int64_t worstFrame(const std::vector<SequenceFrame>& frames);

}  // namespace twinrender::report
