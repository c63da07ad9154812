// A scatter chart as standalone SVG: cost (x) against error (y), one labelled marker per point,
// the Pareto front as a line through the points no other point beats in both. Written for
// `twinrender sweep` (docs/cli.md); no library, the SVG is plain text.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace twinrender::report {

struct ChartPoint {
    double x = 0.0;     // e.g. time in ms; non-finite or (log axis) <= 0: not drawn
    double y = 0.0;     // e.g. an error metric; non-finite: not drawn
    std::string label;  // shown beside the marker; may be empty
};

// The indices of the non-dominated points, by increasing x (ties by better y). Lower x is
// always better; lower y too when `lowerYIsBetter`, else higher y. A point is dominated when
// another is at least as good in both and strictly better in one; of several equal points
// the first is kept. Points with a non-finite x or y take no part.
std::vector<std::size_t> paretoFront(const std::vector<ChartPoint>& points, bool lowerYIsBetter);

enum class AxisScale { Auto, Linear, Log };

struct ScatterChart {
    std::string title;
    std::string xLabel;  // with its unit: "time per frame (ms)"
    std::string yLabel;  // with its unit and direction: "beauty.flip (lower is better)"
    std::vector<ChartPoint> points;
    // The group of each point, by index ("bilateral, sphere"): its colour and legend entry.
    // Empty: one colour for every point, as a sweep draws its combinations.
    std::vector<std::string> groups;
    bool lowerYIsBetter = true;
    // Auto: logarithmic when the positive x values span more than a decade.
    AxisScale xScale = AxisScale::Auto;
    int width = 760;   // px
    int height = 480;  // px
};

// Whether the chart's x axis is logarithmic (xScale, or for Auto the span of the data).
bool usesLogX(const ScatterChart& chart);

// A complete SVG document (XML declaration, <svg> with width, height and viewBox): frame,
// ticks with values, axis labels, a title, one <circle class="point"> per drawn point with a
// <title> and a <text class="point-label">, the Pareto front as <polyline class="pareto">
// (marked points get class="point pareto-point"), and a legend. With groups, each marker also
// has class="group-K" (K = the group's index in order of first appearance; lineSvg's colours
// and markers of series K), a front marker a red ring instead of a red fill, and the legend
// under the plot has one <g class="legend-entry"> per group and one for the front.
std::string scatterSvg(const ScatterChart& chart);

// ---- Line charts: a metric against a setting, one line per series ------------------------

struct LineSeries {
    std::string name;                // the legend's text: "standard depth", "SSSS on"
    std::vector<ChartPoint> points;  // drawn in the order given; labels become marker tooltips
    bool dashed = false;             // e.g. a baseline drawn for comparison
};

struct LineChart {
    std::string title;
    std::string xLabel;  // with its unit: "far / near", "view angle (degrees)"
    std::string yLabel;  // with its unit and direction
    std::vector<LineSeries> series;
    AxisScale xScale = AxisScale::Linear;  // Auto: log when positive x spans more than a decade
    AxisScale yScale = AxisScale::Linear;  // Log: only positive y values are drawn
    // Vertical marks at an x (e.g. where a series breaks): {x, text}.
    std::vector<std::pair<double, std::string>> xMarks;
    // Horizontal bounds at a y (a threshold of the charted metric): {y, text}, drawn as a red
    // dashed line where near the data, else named above the plot as off the chart.
    std::vector<std::pair<double, std::string>> yMarks;
    int width = 760;   // px
    int height = 440;  // px
};

// A complete SVG document like scatterSvg's: frame, ticks with values (at each x value where
// there are at most 8, else round ones; log axes by decades; one notation per axis), axis
// labels, the title, per series a <g class="series" data-colour="..."> with a <polyline
// class="line series-K"> through its drawable points (a break at an undrawable one) and one
// marker (class "point series-K") per drawable point with a <title>; a legend with one <g
// class="legend-entry"> per series, below the plot, wrapped so no entry overlaps another; the
// x marks as <line class="mark">, the bounds as <line class="bound">. Series K has the K-th
// colour of a fixed order in which no two are alike (so equal series orders give equal colours
// across charts), and the (K mod 4)-th marker: circle, square, triangle, diamond.
std::string lineSvg(const LineChart& chart);

}  // namespace twinrender::report
