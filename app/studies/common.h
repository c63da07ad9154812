// What the studies of app/studies/ share: the overrides their points are written with, and the
// rows, numbers and charts their conclusions are drawn from.
#pragma once

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

// ---- a conclusion's rows ----------------------------------------------------------------------

// A row's value of a metric; NaN when it has none.
double metricOf(const StudyRow& r, const std::string& metric);

using SeriesRows = std::vector<std::pair<std::string, std::vector<const StudyRow*>>>;
// The rows of each series, in order of first appearance, each sorted by x.
SeriesRows bySeries(const StudyResult& s);
// The rows of one series of `all`; nullptr when there is no such series.
const std::vector<const StudyRow*>* seriesRows(const SeriesRows& all, const std::string& name);

// The mean of the finite values of a metric over rows; NaN when there are none.
double meanOf(const std::vector<const StudyRow*>& rows, const std::string& metric);

// The gain of series `on` over series `off` per x: 1 - on's metric / off's.
std::map<double, double> gainOf(const StudyResult& s, const std::string& metric,
                                const std::string& on, const std::string& off);

// The lines of a chart: one per series (in order of first appearance) of `metric` against x.
report::LineChart seriesChart(const StudyResult& study, const std::string& metric);

// ---- a finding's numbers ----------------------------------------------------------------------

std::string xNumber(double x);         // a far/near or resolution as people write it: 1e6, 2048
std::string num(double v);             // three significant digits
std::string percent(double fraction);  // "4.2 %", "35 %"
json jsonOrNull(double v);             // null for NaN and infinities

}  // namespace twinrender::app::study
