// What the studies of app/studies/ share: the overrides their points are written with, and the
// rows, numbers and charts their conclusions are drawn from.
#pragma once

#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "report/study_report.h"

namespace twinrender::app::study {

using nlohmann::json;
using report::StudyResult;
using report::StudyRow;

// ---- a point's overrides ----------------------------------------------------------------------

std::string set(const std::string& key, const std::string& value);  // "KEY=VALUE"
std::string vec(double x, double y, double z);                      // "[x, y, z]"

// Focal length in pixels of a camera `height` pixels high with that vertical field of view.
double focalPixels(double height, double fovYDeg);
// `first`, then the camera `distance` along -y from the origin (a scene looking along +y at its
// one body backs away), on a 64 x 48 image when `quick`.
std::vector<std::string> backedAway(std::string first, double distance, bool quick);

// A repeat of a point: the same settings with the camera and its target moved `distance` /
// focal length half a pixel sideways (+x), for a camera at `distance` looking along +y on an
// image `height` pixels high. Both renderers are deterministic, so where the pixel grid falls is
// what differs between two renders of one setting; its series is the original's + REPEAT.
inline constexpr char REPEAT[] = " (repeat)";
std::vector<std::string> halfPixelAside(double distance, double height, double fovYDeg);

// A camera's position and target (scene units) and its up vector, as a scene file gives them.
struct CameraPose {
    std::array<double, 3> position, target, up;
};
// The overrides of a camera at `pose` (camera.position, camera.target), moved half a pixel
// sideways (along the image's +x at the target's distance) when `aside`: a repeat of a point
// for a camera looking any way, on an image `height` pixels high.
std::vector<std::string> cameraAt(const CameraPose& pose, bool aside, double height,
                                  double fovYDeg);

// ---- a conclusion's rows ----------------------------------------------------------------------

// A row's value of a metric; NaN when it has none.
double metricOf(const StudyRow& r, const std::string& metric);

using SeriesRows = std::vector<std::pair<std::string, std::vector<const StudyRow*>>>;
// The rows of each series, in order of first appearance, each sorted by x; repeats left out.
SeriesRows bySeries(const StudyResult& s);
// The rows of one series of `all`; nullptr when there is no such series.
const std::vector<const StudyRow*>* seriesRows(const SeriesRows& all, const std::string& name);

// The mean of the finite values of a metric over rows; NaN when there are none.
double meanOf(const std::vector<const StudyRow*>& rows, const std::string& metric);

// ---- noise: when two values tie ------------------------------------------------------------

// The measured noise of a row's metric: the absolute difference from its repeat's (the row of
// series + REPEAT at the nearest x); NaN when it has no repeat or either value is not finite.
double spreadAt(const StudyResult& s, const StudyRow& r, const std::string& metric);

// How `a` stands to `b` when each may move by its noise: Lower or Higher only when the two are
// further apart than `noise` (the sum of their spreads; NaN, not measured, counts as 0), else
// Tie; Tie when either is not finite.
enum class Order { Lower, Tie, Higher };
Order order(double a, double b, double noise);

// A candidate for "lowest": its name, value and noise (spreadAt).
struct Measured {
    std::string name;
    double value = NAN;
    double spread = 0.0;
};
// The names of the candidates that tie with the lowest (order(value, lowest) is not Higher),
// in the candidates' order; empty when no value is finite.
std::vector<std::string> lowestOf(const std::vector<Measured>& candidates);
// The same for the highest.
std::vector<std::string> highestOf(std::vector<Measured> candidates);
// The standard error of the mean of a metric over rows (repeated measurements of one thing, such
// as a series' frames): the spread a mean of them has; NaN with fewer than two finite values.
double standardErrorOf(const std::vector<const StudyRow*>& rows, const std::string& metric);
// "a", "a and b", "a, b and c".
std::string joinNames(const std::vector<std::string>& names);

// The gain of series `on` over series `off` per x: 1 - on's metric / off's.
std::map<double, double> gainOf(const StudyResult& s, const std::string& metric,
                                const std::string& on, const std::string& off);

// The lines of a chart: one per series (in order of first appearance) of `metric` against x.
report::LineChart seriesChart(const StudyResult& study, const std::string& metric);

// ---- a finding's numbers ----------------------------------------------------------------------

std::string xNumber(double x);         // a far/near or resolution as people write it: 1e6, 2048
std::string num(double v);             // three significant digits; "unmeasured" for NaN, never -0
std::string percent(double fraction);  // "4.2 %", "35 %"; never "-0.0 %"
json jsonOrNull(double v);             // null for NaN and infinities

}  // namespace twinrender::app::study
