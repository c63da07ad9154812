// What the report's pages say about a scene beside its metrics, the same on every page: which
// renderer was measured and its name, the scene's one time per renderer, the devices, the
// metrics that do not apply and the raw files beside the page.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "report/report.h"

namespace twinrender::report {

// The renderer measured against the reference: the built-in real-time one, or the one `run
// --test` named (an external renderer).
std::string testRenderer(const SceneReport& s);

// The two renderers in the order the pages show them: the measured one, then "raymarch".
std::vector<std::string> renderersOf(const SceneReport& s);

// A renderer's name on the pages: "Real-time", "Reference", and an external renderer by its
// program ("External: render.py", from its device "external: python3 render.py").
std::string rendererLabel(const SceneReport& s, const std::string& renderer);

// The label of the scenes' measured renderer when they all share one ("Real-time" when there
// are no scenes), else "Test renderer": the index's column header.
std::string runTestLabel(const RunReport& run);

// The scene's time of a renderer, the one every page shows: its time.<renderer>_ms metric
// (for a sequence the median over the frames), else its frame's total; nullopt for none.
std::optional<double> sceneTimeMs(const SceneReport& s, const std::string& renderer);

// "0.31 ms", "12.4 ms", "1.94 s", "2 min 3 s".
std::string formatMs(double ms);

// The reference's time over the measured renderer's, "0.23×", "340×"; "" without both.
std::string speedRatio(const SceneReport& s);

// What the time is, for a sequence: "median of 5 frames"; "" for a still scene.
std::string timeBasis(const SceneReport& s);

// The renderer's device ("llvmpipe (LLVM 15.0.6, 256 bits)", "2 CPU threads"); "" for none.
std::string deviceOf(const SceneReport& s, const std::string& renderer);

// True when the measured renderer ran on a software rasteriser (llvmpipe): its times are then
// the CPU's.
bool ranOnSoftwareRasteriser(const SceneReport& s);

// The plain words for that case, naming the device: HTML, one paragraph.
std::string softwareRasteriserNote(const std::string& device);

// True when the metric does not apply to the scene (SceneReport::notApplicable).
bool isNotApplicable(const SceneReport& s, const std::string& metric);

// The worst status of the metric's checks; nullopt when it has none.
std::optional<compare::Status> metricStatus(const SceneReport& s, const std::string& metric);

// A metric's value as a table cell, coloured by its checks with their messages as the
// tooltip; "n/a" with the reason for a metric that does not apply, "—" for one not computed.
// `thresholdsFile` names where a missing bound would go, in the tooltip of an unbounded value.
std::string valueCell(const SceneReport& s, const std::string& metric,
                      const std::string& thresholdsFile = "");

// "3 scenes: 2 pass, 1 fail".
std::string countsText(const std::vector<compare::Status>& statuses, std::string_view noun);

// The failed and warned checks' messages, failures first; an error that stopped the scene
// before them.
std::vector<std::pair<compare::Status, std::string>> problemsOf(const SceneReport& s);

// The raw files of the scene beside its page, as {text, path relative to the page}: each
// renderer's AOV image and frame JSON beside its beauty PNG (where `run` writes them; none for
// a renderer without images), metrics.json and a sequence's videos.
std::vector<std::pair<std::string, std::string>> rawFiles(const SceneReport& s);

}  // namespace twinrender::report
