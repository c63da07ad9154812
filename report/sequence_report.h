// The sequence part of a scene's report (report.h SequenceReport): a chart of every metric
// over the frames and the scene page's "Sequence" section, with the side-by-side video, the
// charts and a table of every frame's metrics.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "report/report.h"

namespace twinrender::report {

// Writes DIR/charts/<metric>.svg for every metric the frames have (lineSvg: the metric against
// the frame number, with its `bounds` drawn; temporal.frame_flip and temporal.normal_change_deg
// with the reference's change beside them, dashed, and no charts of their own for those) and
// returns metric -> path relative to DIR, for SequenceReport::charts. A metric that does not
// apply to any frame, or has one value in every frame, gets no chart (the frames' table has
// it).
std::map<std::string, std::string> writeSequenceCharts(const SequenceReport& sequence,
                                                       const std::filesystem::path& dir,
                                                       const compare::Bounds& bounds = {});

// The scene page's <section> of a sequence: its facts, the video (WebM first, then MP4), the
// charts and the frames' table; "" for a scene that is not a sequence.
std::string sequenceSection(const SceneReport& scene);

}  // namespace twinrender::report
