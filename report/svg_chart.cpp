#include "report/svg_chart.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "report/markup.h"

namespace twinrender::report {

namespace {

// Okabe and Ito's colour-blind-safe eight (2008), then four darker or lighter kin of them
// told apart by their markers, in a fixed order so that series keep their colour.
constexpr const char* PALETTE[12] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7",
                                     "#e69f00", "#56b4e9", "#000000", "#f0e442",
                                     "#7a3e00", "#00468b", "#8f8f8f", "#7b1f5e"};
constexpr std::size_t PALETTE_SIZE = sizeof(PALETTE) / sizeof(PALETTE[0]);

// The colour of series or group k: the palette's, then hues a golden angle apart, so no two
// of any chart's series share one.
std::string seriesColour(std::size_t k) {
    if (k < PALETTE_SIZE) return PALETTE[k];
    const double hue = std::fmod(37.0 + 137.508 * static_cast<double>(k), 360.0);
    return fmt::format("hsl({:.0f},70%,{}%)", hue, k % 2 ? 35 : 50);
}

// The marker of series or group k, a second cue beside the colour: circle, square, triangle,
// diamond in turn. `cls` carries "point" and the series' class.
std::string marker(std::size_t k, const std::string& cls, double x, double y, double r,
                   const std::string& inner = "") {
    const std::string end = inner.empty() ? "/>" : ">" + inner;
    switch (k % 4) {
        case 1:
            return fmt::format(
                "<rect class=\"{}\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" "
                "height=\"{:.1f}\"{}{}",
                cls, x - 0.85 * r, y - 0.85 * r, 1.7 * r, 1.7 * r, end,
                inner.empty() ? "" : "</rect>");
        case 2:
            return fmt::format(
                "<path class=\"{}\" d=\"M{:.1f},{:.1f}L{:.1f},{:.1f}L{:.1f},{:.1f}Z\"{}{}", cls, x,
                y - 1.15 * r, x + r, y + 0.75 * r, x - r, y + 0.75 * r, end,
                inner.empty() ? "" : "</path>");
        case 3:
            return fmt::format(
                "<path class=\"{}\" "
                "d=\"M{:.1f},{:.1f}L{:.1f},{:.1f}L{:.1f},{:.1f}L{:.1f},{:.1f}Z\"{}{}",
                cls, x, y - 1.2 * r, x + 1.2 * r, y, x, y + 1.2 * r, x - 1.2 * r, y, end,
                inner.empty() ? "" : "</path>");
        default:
            return fmt::format("<circle class=\"{}\" cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{}\"{}{}", cls,
                               x, y, r, end, inner.empty() ? "" : "</circle>");
    }
}

bool drawable(const ChartPoint& p, bool logX) {
    return std::isfinite(p.x) && std::isfinite(p.y) && (!logX || p.x > 0.0);
}

// Titles, labels and tick texts go both into text nodes and attributes: escape for both.
std::string xmlText(std::string_view s) {
    return xmlEscape(s, true);
}

// Whether a value is written with an exponent: beyond 1e5 or under 1e-3.
bool needsExponent(double v) {
    const double a = std::abs(v);
    return v != 0.0 && (a >= 1e5 || a < 1e-3);
}

// A tick value as people write it: 0.05, 2, 1e+06; with an exponent when `exponent`.
std::string tickText(double v, bool exponent) {
    if (v == 0.0) return "0";
    if (!exponent) return fmt::format("{:.6g}", v);
    const int e = static_cast<int>(std::floor(std::log10(std::abs(v)) + 1e-9));
    return fmt::format("{:.3g}e{}{:02d}", v / std::pow(10.0, e), e < 0 ? '-' : '+', std::abs(e));
}

std::string tickText(double v) {
    return tickText(v, needsExponent(v));
}

// One axis's tick texts in one notation: every one with an exponent when any needs one, so an
// axis never mixes 10000 and 1e+05.
std::vector<std::string> tickTexts(const std::vector<double>& ticks) {
    const bool exponent = std::any_of(ticks.begin(), ticks.end(), needsExponent);
    std::vector<std::string> out;
    for (double t : ticks) out.push_back(tickText(t, exponent));
    return out;
}

// Linear ticks at 1, 2 or 5 times a power of ten, about `target` of them over [lo, hi].
std::vector<double> linearTicks(double lo, double hi, int target) {
    const double span = hi - lo;
    const double raw = span / std::max(target, 1);
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    double step = mag;
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * mag >= raw) {
            step = m * mag;
            break;
        }
    std::vector<double> ticks;
    for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step)
        ticks.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
    return ticks;
}

// Log ticks: every decade, and 2 and 5 between them when there are few decades.
std::vector<double> logTicks(double lo, double hi) {
    const int d0 = static_cast<int>(std::floor(std::log10(lo)));
    const int d1 = static_cast<int>(std::ceil(std::log10(hi)));
    std::vector<double> ticks;
    for (int d = d0; d <= d1; ++d)
        for (double m : d1 - d0 <= 3 ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
            const double t = m * std::pow(10.0, d);
            if (t >= lo * (1 - 1e-9) && t <= hi * (1 + 1e-9)) ticks.push_back(t);
        }
    return ticks;
}

struct Axis {
    double lo, hi;
    bool log;
    double pixLo, pixHi;  // screen coordinates of lo and hi
    double map(double v) const {
        const double f = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))
                             : (v - lo) / (hi - lo);
        return pixLo + f * (pixHi - pixLo);
    }
};

// The grid lines and tick labels at the given ticks, then the plot's frame (the axes' pixel
// ranges: x from left to right, y from bottom to top).
std::string gridAndFrame(const Axis& ax, const Axis& ay, const std::vector<double>& xt,
                         const std::vector<double>& yt) {
    const double left = ax.pixLo, right = ax.pixHi, bottom = ay.pixLo, top = ay.pixHi;
    std::string s = "<g class=\"ticks\">\n";
    const std::vector<std::string> xTexts = tickTexts(xt), yTexts = tickTexts(yt);
    // A label that would touch the last one drawn keeps its grid line only (6.5 px a character
    // at 11 px).
    double lastEnd = -INFINITY;
    for (std::size_t i = 0; i < xt.size(); ++i) {
        const double px = ax.map(xt[i]);
        const double half = 3.25 * static_cast<double>(xTexts[i].size());
        const bool label = px - half > lastEnd + 4.0;
        if (label) lastEnd = px + half;
        s += fmt::format(
            "<line class=\"grid\" x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\"/>",
            px, top, bottom);
        if (label)
            s += fmt::format(
                "<text class=\"tick\" x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>",
                px, bottom + 16, xmlText(xTexts[i]));
        s += "\n";
    }
    for (std::size_t i = 0; i < yt.size(); ++i) {
        const double py = ay.map(yt[i]);
        s += fmt::format(
            "<line class=\"grid\" x1=\"{1:.1f}\" y1=\"{0:.1f}\" x2=\"{2:.1f}\" y2=\"{0:.1f}\"/>"
            "<text class=\"tick\" x=\"{3:.1f}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>\n",
            py, left, right, left - 6, py + 4, xmlText(yTexts[i]));
    }
    s += "</g>\n";
    s += fmt::format("<rect class=\"axis\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>\n", left,
                     top, right - left, bottom - top);
    return s;
}

// The data range padded so that markers do not sit on the frame.
std::pair<double, double> paddedRange(double lo, double hi, bool log) {
    if (log) {
        if (hi <= lo) return {lo / 2, hi * 2};
        const double f = std::pow(hi / lo, 0.06);
        return {lo / f, hi * f};
    }
    if (hi <= lo) {
        const double d = lo == 0.0 ? 1.0 : std::abs(lo) * 0.1;
        return {lo - d, hi + d};
    }
    const double pad = (hi - lo) * 0.06;
    return {lo - pad, hi + pad};
}

// The XML declaration, the <svg> element, the style sheet (the shared rules around a chart's
// own: `styles` after the tick rule, `after` at the end), the white background and the title.
std::string chartOpening(int width, int height, const std::string& title, double titleX,
                         std::string_view styles, std::string_view after) {
    std::string s = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    s += fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" "
        "viewBox=\"0 0 {0} {1}\" font-family=\"DejaVu Sans, Arial, sans-serif\" "
        "font-size=\"12\">\n",
        width, height);
    s += "<style>.grid{stroke:#e1e4e8;stroke-width:1}.axis{stroke:#57606a;stroke-width:1;fill:none}"
         ".tick{fill:#57606a;font-size:11px}";
    s += styles;
    s += ".title{font-size:15px;font-weight:600;fill:#24292f}.label{fill:#24292f;font-size:12px}";
    s += after;
    s += "</style>\n";
    s += fmt::format("<rect x=\"0\" y=\"0\" width=\"{}\" height=\"{}\" fill=\"#ffffff\"/>\n",
                     double(width), double(height));
    s += fmt::format("<text class=\"title\" x=\"{}\" y=\"24\">{}</text>\n", titleX, xmlText(title));
    return s;
}

// Where each legend entry goes, under the plot from `top`: left to right, a new row where the
// next would pass `right` (an entry is its 30 px sample and its text at 6.5 px a character).
struct LegendLayout {
    std::vector<std::pair<double, double>> at;  // each entry's sample's left end and middle
    int rows = 0;
};
LegendLayout legendLayout(const std::vector<std::string>& names, double left, double right,
                          double top) {
    LegendLayout l;
    double x = left;
    for (const std::string& n : names) {
        const double w = 30.0 + 6.5 * static_cast<double>(n.size()) + 18.0;
        if (l.rows == 0 || (x + w > right && x > left)) {
            x = left;
            ++l.rows;
        }
        l.at.emplace_back(x, top + 18.0 * (l.rows - 1));
        x += w;
    }
    return l;
}

std::string frontName(bool lowerYIsBetter) {
    return fmt::format("Pareto front (nothing is both faster and {})",
                       lowerYIsBetter ? "lower" : "higher");
}

// The legend of an ungrouped scatter, between the title and the plot: a setting, the front.
std::string frontLegend(bool lowerYIsBetter, double lx, double ly) {
    std::string s = "<g class=\"legend\">\n";
    s += fmt::format(
        "<circle class=\"point\" cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"5\"/>"
        "<text class=\"label\" x=\"{:.1f}\" y=\"{:.1f}\">setting</text>\n",
        lx, ly, lx + 10, ly + 4);
    s += fmt::format(
        "<line class=\"pareto\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\"/>"
        "<circle class=\"point pareto-point\" cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"5\"/>"
        "<text class=\"label\" x=\"{:.1f}\" y=\"{:.1f}\">Pareto front (nothing is both "
        "faster and {})</text>\n",
        lx + 70, ly, lx + 100, ly, lx + 85, ly, lx + 106, ly + 4,
        lowerYIsBetter ? "lower" : "higher");
    return s + "</g>\n";
}

// The legend of a grouped scatter, under the plot from `top`: one <g class="legend-entry"> per
// group in its colour and marker, then the front.
std::string groupLegend(const std::vector<std::string>& groups, bool lowerYIsBetter, double left,
                        double right, double top) {
    std::vector<std::string> names = groups;
    names.push_back(frontName(lowerYIsBetter));
    const LegendLayout l = legendLayout(names, left, right, top);
    std::string s = "<g class=\"legend\">\n";
    for (std::size_t k = 0; k < names.size(); ++k) {
        const auto [lx, ly] = l.at[k];
        if (k < groups.size())
            s += "<g class=\"legend-entry\">" +
                 marker(k, fmt::format("point group-{}", k), lx + 6, ly, 5) +
                 fmt::format("<text class=\"label\" x=\"{:.1f}\" y=\"{:.1f}\">{}</text></g>\n",
                             lx + 16, ly + 4, xmlText(names[k]));
        else
            s += fmt::format(
                "<g class=\"legend-entry\"><line class=\"pareto\" x1=\"{:.1f}\" y1=\"{:.1f}\" "
                "x2=\"{:.1f}\" y2=\"{:.1f}\"/><text class=\"label\" x=\"{:.1f}\" "
                "y=\"{:.1f}\">{}</text></g>\n",
                lx, ly, lx + 24, ly, lx + 30, ly + 4, xmlText(names[k]));
    }
    return s + "</g>\n";
}

}  // namespace

std::vector<std::size_t> paretoFront(const std::vector<ChartPoint>& points, bool lowerYIsBetter) {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (std::isfinite(points[i].x) && std::isfinite(points[i].y)) order.push_back(i);
    // y as a cost: lower is better in both coordinates.
    auto cost = [&](std::size_t i) { return lowerYIsBetter ? points[i].y : -points[i].y; };
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        if (points[a].x != points[b].x) return points[a].x < points[b].x;
        return cost(a) < cost(b);
    });
    // Swept by increasing x: a point is on the front when it beats every cheaper point's y.
    std::vector<std::size_t> front;
    for (std::size_t i : order)
        if (front.empty() || cost(i) < cost(front.back())) front.push_back(i);
    return front;
}

bool usesLogX(const ScatterChart& chart) {
    if (chart.xScale != AxisScale::Auto) return chart.xScale == AxisScale::Log;
    double lo = INFINITY, hi = 0.0;
    for (const ChartPoint& p : chart.points)
        if (drawable(p, true)) {
            lo = std::min(lo, p.x);
            hi = std::max(hi, p.x);
        }
    return hi > 0.0 && hi / lo > 10.0;
}

std::string scatterSvg(const ScatterChart& chart) {
    const bool logX = usesLogX(chart);
    const double W = chart.width, H = chart.height;
    // The groups in order of first appearance; none: one colour, the legend above the plot.
    std::vector<std::string> groups;
    for (const std::string& g : chart.groups)
        if (std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
    auto groupOf = [&](std::size_t i) -> std::string {
        return i < chart.groups.size() ? chart.groups[i] : std::string();
    };
    auto groupIndex = [&](std::size_t i) {
        return static_cast<std::size_t>(std::find(groups.begin(), groups.end(), groupOf(i)) -
                                        groups.begin());
    };
    // Groups: a legend under the plot, 4 entries a row, the front's entry last.
    std::vector<std::string> legendNames = groups;
    legendNames.push_back(frontName(chart.lowerYIsBetter));
    const int legendRows = groups.empty() ? 0 : legendLayout(legendNames, 78, W - 24, 0).rows;
    // Plot area: room on the left for y tick values, below for x ticks and the axis label,
    // above for the title, on the right for the legend and point labels.
    const double left = 78, right = W - 24, top = groups.empty() ? 64 : 44,
                 bottom = H - 62 - 18.0 * legendRows;

    std::vector<std::size_t> shown;
    for (std::size_t i = 0; i < chart.points.size(); ++i)
        if (drawable(chart.points[i], logX)) shown.push_back(i);
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (std::size_t i : shown) {
        x0 = std::min(x0, chart.points[i].x);
        x1 = std::max(x1, chart.points[i].x);
        y0 = std::min(y0, chart.points[i].y);
        y1 = std::max(y1, chart.points[i].y);
    }
    if (shown.empty()) {
        x0 = logX ? 1.0 : 0.0;
        x1 = logX ? 10.0 : 1.0;
        y0 = 0.0;
        y1 = 1.0;
    }
    const auto [xl, xh] = paddedRange(x0, x1, logX);
    const auto [yl, yh] = paddedRange(y0, y1, false);
    const Axis ax{xl, xh, logX, left, right};
    const Axis ay{yl, yh, false, bottom, top};

    std::string s =
        chartOpening(chart.width, chart.height, chart.title, left,
                     ".point{fill:#0969da;fill-opacity:0.75;stroke:#ffffff;stroke-width:1}"
                     ".pareto-point{fill:#cf222e}.pareto{stroke:#cf222e;stroke-width:2;"
                     "fill:none}.point-label{fill:#24292f;font-size:10px}",
                     [&] {
                         // A group's colour; its points on the front get a red ring.
                         std::string g;
                         for (std::size_t k = 0; k < groups.size(); ++k)
                             g += fmt::format(".point.group-{}{{fill:{}}}", k, seriesColour(k));
                         if (!groups.empty())
                             g += ".point.pareto-point{fill-opacity:1;stroke:#cf222e;stroke-width:"
                                  "2.5}";
                         return g;
                     }());

    // Grid and ticks.
    const std::vector<double> xt = logX ? logTicks(xl, xh) : linearTicks(xl, xh, 6);
    const std::vector<double> yt = linearTicks(yl, yh, 6);
    s += gridAndFrame(ax, ay, xt, yt);
    s += fmt::format(
        "<text class=\"label\" x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}{}</text>\n",
        (left + right) / 2, bottom + 40, xmlText(chart.xLabel), logX ? " — log scale" : "");
    s += fmt::format(
        "<text class=\"label\" transform=\"translate(18 {:.1f}) rotate(-90)\" "
        "text-anchor=\"middle\">{}</text>\n",
        (top + bottom) / 2, xmlText(chart.yLabel));

    // The Pareto front under the markers.
    const std::vector<std::size_t> front = paretoFront(
        [&] {
            std::vector<ChartPoint> pts = chart.points;
            for (ChartPoint& p : pts)
                if (!drawable(p, logX)) p.x = NAN;
            return pts;
        }(),
        chart.lowerYIsBetter);
    if (!front.empty()) {
        s += "<polyline class=\"pareto\" points=\"";
        for (std::size_t k = 0; k < front.size(); ++k)
            s += fmt::format("{}{:.1f},{:.1f}", k ? " " : "", ax.map(chart.points[front[k]].x),
                             ay.map(chart.points[front[k]].y));
        s += "\"/>\n";
    }
    s += "<g class=\"points\">\n";
    // Labels beside their markers: right of the marker (left near the right edge), else on the
    // other side, else moved up or down past labels already placed (estimated widths: 6 px per
    // character at 10 px).
    struct Box {
        double x0, y0, x1, y1;
    };
    std::vector<Box> placed;
    for (std::size_t i : shown) {
        const ChartPoint& p = chart.points[i];
        const double px = ax.map(p.x), py = ay.map(p.y);
        placed.push_back({px - 5, py - 5, px + 5, py + 5});
    }
    for (std::size_t i : shown) {
        const ChartPoint& p = chart.points[i];
        const bool onFront = std::find(front.begin(), front.end(), i) != front.end();
        const double px = ax.map(p.x), py = ay.map(p.y);
        const std::size_t g = groups.empty() ? 0 : groupIndex(i);
        s += marker(g,
                    fmt::format("point{}{}", onFront ? " pareto-point" : "",
                                groups.empty() ? "" : fmt::format(" group-{}", g)),
                    px, py, 5,
                    fmt::format("<title>{}{} — x {}, y {}</title>",
                                groupOf(i).empty() ? "" : xmlText(groupOf(i)) + " ",
                                xmlText(p.label), xmlText(tickText(p.x)), xmlText(tickText(p.y))));
        if (!p.label.empty()) {
            const double w = 6.0 * static_cast<double>(p.label.size());
            const bool rightFits = px + 8 + w <= W - 4, leftFits = px - 8 - w >= 4;
            const bool preferLeft = !rightFits && leftFits;
            bool left = preferLeft;
            double y = py - 6;
            bool done = false;
            for (double dy : {0.0, 14.0, -12.0, 26.0, -24.0, 38.0, -36.0}) {
                for (const bool side : {preferLeft, !preferLeft}) {
                    if (side != preferLeft && !(side ? leftFits : rightFits)) continue;
                    const double x0 = side ? px - 8 - w : px + 8;
                    const Box b{x0, py - 6 + dy - 9, x0 + w, py - 6 + dy + 2};
                    const bool clash = std::any_of(placed.begin(), placed.end(), [&](const Box& o) {
                        return b.x0 < o.x1 && o.x0 < b.x1 && b.y0 < o.y1 && o.y0 < b.y1;
                    });
                    if (!clash || (dy == -36.0 && side == preferLeft)) {
                        y = py - 6 + dy;
                        left = side;
                        placed.push_back(b);
                        done = true;
                        break;
                    }
                }
                if (done) break;
            }
            s += fmt::format("<text class=\"point-label\" x=\"{:.1f}\" y=\"{:.1f}\"{}>{}</text>",
                             left ? px - 8 : px + 8, y, left ? " text-anchor=\"end\"" : "",
                             xmlText(p.label));
        }
        s += "\n";
    }
    s += "</g>\n";

    if (!groups.empty()) {
        s += groupLegend(groups, chart.lowerYIsBetter, left, right, bottom + 56);
    } else {
        s += frontLegend(chart.lowerYIsBetter, left + 6, 44);
    }
    if (shown.size() < chart.points.size())
        s += fmt::format(
            "<text class=\"tick\" x=\"{}\" y=\"{:.1f}\">{} of {} points not drawn (no finite "
            "value)</text>\n",
            left, H - 6, chart.points.size() - shown.size(), chart.points.size());
    s += "</svg>\n";
    return s;
}

namespace {

bool usesLog(AxisScale scale, const std::vector<double>& values) {
    if (scale != AxisScale::Auto) return scale == AxisScale::Log;
    double lo = INFINITY, hi = 0.0;
    for (double v : values)
        if (std::isfinite(v) && v > 0.0) {
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    return hi > 0.0 && hi / lo > 10.0;
}

}  // namespace

std::string lineSvg(const LineChart& chart) {
    std::vector<double> xs, ys;
    for (const LineSeries& ls : chart.series)
        for (const ChartPoint& p : ls.points) {
            xs.push_back(p.x);
            ys.push_back(p.y);
        }
    const bool logX = usesLog(chart.xScale, xs);
    const bool logY = usesLog(chart.yScale, ys);
    auto drawn = [&](const ChartPoint& p) {
        return std::isfinite(p.x) && std::isfinite(p.y) && (!logX || p.x > 0.0) &&
               (!logY || p.y > 0.0);
    };
    const double W = chart.width, H = chart.height;
    std::vector<std::string> names;
    for (const LineSeries& ls : chart.series) names.push_back(ls.name);
    const int legendRows = legendLayout(names, 78, W - 24, 0).rows;
    const double left = 78, right = W - 24, top = 44, bottom = H - 62 - 18.0 * legendRows;

    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    std::size_t total = 0, shown = 0;
    std::vector<double> dataX;  // the distinct drawn x values
    for (const LineSeries& ls : chart.series)
        for (const ChartPoint& p : ls.points) {
            ++total;
            if (!drawn(p)) continue;
            ++shown;
            x0 = std::min(x0, p.x);
            x1 = std::max(x1, p.x);
            y0 = std::min(y0, p.y);
            y1 = std::max(y1, p.y);
            if (std::find(dataX.begin(), dataX.end(), p.x) == dataX.end()) dataX.push_back(p.x);
        }
    for (const auto& [x, text] : chart.xMarks)
        if (std::isfinite(x) && (!logX || x > 0.0) && shown) {
            x0 = std::min(x0, x);
            x1 = std::max(x1, x);
        }
    // A bound is drawn where it is near the data (within the data's span again), so that a
    // far one does not flatten the lines; those beyond are named above the plot.
    std::vector<std::pair<double, std::string>> bounds, farBounds;
    for (const auto& [y, text] : chart.yMarks) {
        if (!std::isfinite(y) || (logY && y <= 0.0) || !shown) continue;
        const double span = std::max(y1 - y0, std::abs(y1) * 0.5);
        const bool near =
            logY ? (y >= y0 / 10.0 && y <= y1 * 10.0) : (y >= y0 - span && y <= y1 + span);
        (near ? bounds : farBounds).emplace_back(y, text);
    }
    for (const auto& [y, text] : bounds) {
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
    }
    if (!shown) {
        x0 = logX ? 1.0 : 0.0;
        x1 = logX ? 10.0 : 1.0;
        y0 = logY ? 1.0 : 0.0;
        y1 = logY ? 10.0 : 1.0;
    }
    // A linear error axis starts at 0 when the data are not far from it: errors read as sizes.
    if (!logY && y0 > 0.0 && y0 < 0.5 * y1) y0 = 0.0;
    const auto [xl, xh] = paddedRange(x0, x1, logX);
    auto [yl, yh] = paddedRange(y0, y1, logY);
    if (!logY && y0 == 0.0 && y1 > 0.0) yl = 0.0;
    const Axis ax{xl, xh, logX, left, right};
    const Axis ay{yl, yh, logY, bottom, top};

    std::string series;
    for (std::size_t k = 0; k < chart.series.size(); ++k)
        series += fmt::format(".series-{0}.line{{stroke:{1}}}.series-{0}.point{{fill:{1}}}", k,
                              seriesColour(k));
    std::string s = chartOpening(chart.width, chart.height, chart.title, left,
                                 ".line{fill:none;stroke-width:2}.dashed{stroke-dasharray:6 4}"
                                 ".point{stroke:#ffffff;stroke-width:1}.mark{stroke:#8c959f;"
                                 "stroke-width:1;stroke-dasharray:3 3}.mark-label{fill:#57606a;"
                                 "font-size:10px}.bound{stroke:#cf222e;stroke-width:1.5;"
                                 "stroke-dasharray:8 3}.bound-label{fill:#cf222e;font-size:10px}",
                                 series);

    // Few x values: a tick at each (a study's 64, 256, 1024), else round ones.
    std::sort(dataX.begin(), dataX.end());
    const bool atData = !dataX.empty() && dataX.size() <= 8;
    const std::vector<double> xt = atData ? dataX
                                   : logX ? logTicks(xl, xh)
                                          : linearTicks(xl, xh, 6);
    std::vector<double> yt = logY ? logTicks(yl, yh) : linearTicks(yl, yh, 6);
    // Many decades: every other one keeps the labels apart.
    auto thin = [](std::vector<double> t, std::size_t most) {
        while (t.size() > most) {
            std::vector<double> half;
            for (std::size_t i = 0; i < t.size(); i += 2) half.push_back(t[i]);
            t = std::move(half);
        }
        return t;
    };
    const std::vector<double> xtShown = thin(xt, 12);
    yt = thin(yt, 10);
    s += gridAndFrame(ax, ay, xtShown, yt);
    s += fmt::format(
        "<text class=\"label\" x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}{}</text>\n",
        (left + right) / 2, bottom + 36, xmlText(chart.xLabel), logX ? " — log scale" : "");
    s += fmt::format(
        "<text class=\"label\" transform=\"translate(18 {:.1f}) rotate(-90)\" "
        "text-anchor=\"middle\">{}{}</text>\n",
        (top + bottom) / 2, xmlText(chart.yLabel), logY ? " — log scale" : "");

    for (const auto& [x, text] : chart.xMarks) {
        if (!std::isfinite(x) || (logX && x <= 0.0) || !shown) continue;
        const double px = ax.map(x);
        // Right of the line, or left of it where the text would leave the plot.
        const bool flip = px + 3 + 6.0 * static_cast<double>(text.size()) > right;
        s += fmt::format(
            "<line class=\"mark\" x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\"/>"
            "<text class=\"mark-label\" x=\"{3:.1f}\" y=\"{4:.1f}\"{5}>{6}</text>\n",
            px, top, bottom, flip ? px - 3 : px + 3, top + 11, flip ? " text-anchor=\"end\"" : "",
            xmlText(text));
    }
    for (const auto& [y, text] : bounds) {
        const double py = ay.map(y);
        s += fmt::format(
            "<line class=\"bound\" x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\"/>"
            "<text class=\"bound-label\" x=\"{3:.1f}\" y=\"{4:.1f}\" "
            "text-anchor=\"end\">{5}</text>\n",
            left, py, right, right - 4, py - 4, xmlText(text));
    }
    // The bounds far from the data, in one line above the plot's right corner.
    if (!farBounds.empty()) {
        std::string names;
        for (const auto& [y, text] : farBounds) names += (names.empty() ? "" : ", ") + text;
        s += fmt::format(
            "<text class=\"bound-label\" x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"end\">{}: off "
            "the chart</text>\n",
            right, top - 6, xmlText(names));
    }

    for (std::size_t k = 0; k < chart.series.size(); ++k) {
        const LineSeries& ls = chart.series[k];
        const std::string cls = fmt::format("series-{}", k);
        s += fmt::format("<g class=\"series\" data-series=\"{}\" data-colour=\"{}\">\n",
                         xmlText(ls.name), seriesColour(k));
        // A line through consecutive drawable points; an undrawable point breaks it.
        std::vector<std::string> runs(1);
        for (const ChartPoint& p : ls.points) {
            if (!drawn(p)) {
                if (!runs.back().empty()) runs.emplace_back();
                continue;
            }
            runs.back() += fmt::format("{}{:.1f},{:.1f}", runs.back().empty() ? "" : " ",
                                       ax.map(p.x), ay.map(p.y));
        }
        for (const std::string& r : runs)
            if (r.find(' ') != std::string::npos)
                s += fmt::format("<polyline class=\"line {}{}\" points=\"{}\"/>\n", cls,
                                 ls.dashed ? " dashed" : "", r);
        for (const ChartPoint& p : ls.points) {
            if (!drawn(p)) continue;
            s += marker(k, "point " + cls, ax.map(p.x), ay.map(p.y), 4,
                        fmt::format("<title>{}{}x {}, y {}</title>", xmlText(ls.name),
                                    p.label.empty() ? " — " : " — " + xmlText(p.label) + ": ",
                                    xmlText(tickText(p.x)), xmlText(fmt::format("{:.4g}", p.y)))) +
                 "\n";
        }
        s += "</g>\n";
    }

    s += "<g class=\"legend\">\n";
    const LegendLayout legend = legendLayout(names, left, right, bottom + 56);
    for (std::size_t k = 0; k < chart.series.size(); ++k) {
        const auto [lx, ly] = legend.at[k];
        const std::string cls = fmt::format("series-{}", k);
        s += fmt::format(
                 "<g class=\"legend-entry\"><line class=\"line {0}{1}\" x1=\"{2:.1f}\" "
                 "y1=\"{3:.1f}\" x2=\"{4:.1f}\" y2=\"{3:.1f}\"/>",
                 cls, chart.series[k].dashed ? " dashed" : "", lx, ly, lx + 24) +
             marker(k, "point " + cls, lx + 12, ly, 4) +
             fmt::format("<text class=\"label\" x=\"{:.1f}\" y=\"{:.1f}\">{}</text></g>\n", lx + 30,
                         ly + 4, xmlText(chart.series[k].name));
    }
    s += "</g>\n";
    if (shown < total)
        s += fmt::format(
            "<text class=\"tick\" x=\"{}\" y=\"{:.1f}\">{} of {} points not drawn (no finite{} "
            "value)</text>\n",
            left, H - 4, total - shown, total, logX || logY ? " positive" : "");
    s += "</svg>\n";
    return s;
}

}  // namespace twinrender::report
