#include "report/svg_chart.h"

#include <gtest/gtest.h>

#include <cmath>

#include "report/testdata/xml_check.h"

namespace tc = twinrender::report;

TEST(ParetoFront, KeepsThePointsNothingBeatsInBoth) {
    // (time, error): c is beaten by b (faster and better), e by d; the rest trade off.
    const std::vector<tc::ChartPoint> pts = {
        {10.0, 0.05, "a"}, {2.0, 0.20, "b"}, {3.0, 0.25, "c"}, {5.0, 0.10, "d"}, {6.0, 0.12, "e"}};
    EXPECT_EQ(tc::paretoFront(pts, true), (std::vector<std::size_t>{1, 3, 0}));
    // Higher is better (e.g. SSIM): only the fastest point and the best ones survive.
    const std::vector<tc::ChartPoint> ssim = {
        {1.0, 0.80, "a"}, {2.0, 0.95, "b"}, {3.0, 0.90, "c"}, {4.0, 0.99, "d"}};
    EXPECT_EQ(tc::paretoFront(ssim, false), (std::vector<std::size_t>{0, 1, 3}));
}

TEST(ParetoFront, TiesAndNonFiniteValues) {
    // Equal points: the first is kept. Same time, worse error: dominated. NaN: no part.
    const std::vector<tc::ChartPoint> pts = {{1.0, 0.5, "a"},        {1.0, 0.5, "a again"},
                                             {1.0, 0.7, "worse"},    {NAN, 0.0, "nan"},
                                             {0.5, INFINITY, "inf"}, {2.0, 0.1, "b"}};
    EXPECT_EQ(tc::paretoFront(pts, true), (std::vector<std::size_t>{0, 5}));
    EXPECT_TRUE(tc::paretoFront({}, true).empty());
}

TEST(ScatterSvg, IsWellFormedWithOneMarkerPerPoint) {
    tc::ScatterChart chart;
    chart.title = "planet: time against <error> & more";
    chart.xLabel = "time per frame (ms)";
    chart.yLabel = "beauty.flip (lower is better)";
    chart.points = {{1.5, 0.2, "ssss.enabled=true"},
                    {3.0, 0.1, "a \"quoted\" label"},
                    {2.0, 0.3, "x<y"},
                    {4.0, 0.05, ""}};
    const std::string svg = tc::scatterSvg(chart);
    const auto xml = twinrender::test::checkXml(svg);
    ASSERT_EQ(xml.error, "") << svg;
    // Four markers plus the two legend markers; three of them on the front (+1 in the legend).
    EXPECT_EQ(xml.classCounts.at("point"), 4 + 2);
    EXPECT_EQ(xml.classCounts.at("pareto-point"), 3 + 1);
    EXPECT_EQ(xml.classCounts.at("point-label"), 3);
    EXPECT_EQ(xml.elementCounts.at("polyline"), 1);
    EXPECT_NE(svg.find("width=\"760\""), std::string::npos);
    EXPECT_NE(svg.find("time per frame (ms)"), std::string::npos);
    EXPECT_NE(svg.find("Pareto front"), std::string::npos);
    EXPECT_EQ(svg.find("log scale"), std::string::npos);  // 1.5..4 ms: linear
}

TEST(ScatterSvg, LogAxisWhenTimesSpanDecades) {
    tc::ScatterChart chart;
    chart.xLabel = "time (ms)";
    chart.yLabel = "error";
    chart.points = {{0.5, 0.3, "fast"}, {40.0, 0.1, "mid"}, {2000.0, 0.01, "slow"}};
    EXPECT_TRUE(tc::usesLogX(chart));
    const std::string svg = tc::scatterSvg(chart);
    EXPECT_EQ(twinrender::test::checkXml(svg).error, "") << svg;
    EXPECT_NE(svg.find("log scale"), std::string::npos);
    // Decade ticks are labelled.
    EXPECT_NE(svg.find(">100</text>"), std::string::npos) << svg;
    chart.xScale = tc::AxisScale::Linear;
    EXPECT_FALSE(tc::usesLogX(chart));
}

TEST(ScatterSvg, GroupsGetAColourAndALegendEntryEach) {
    tc::ScatterChart chart;
    chart.xLabel = "time (ms)";
    chart.yLabel = "normal.mean_deg";
    // Two groups; the front is a1 (fastest), b1 (better), a2 (best).
    chart.points = {{1.0, 5.0, "a1"}, {2.0, 4.0, "b1"}, {3.0, 4.5, "b2"}, {4.0, 3.0, "a2"}};
    chart.groups = {"ssss, sphere", "bilateral, sphere", "bilateral, sphere", "ssss, sphere"};
    const std::string svg = tc::scatterSvg(chart);
    const auto xml = twinrender::test::checkXml(svg);
    ASSERT_EQ(xml.error, "") << svg;
    // Four markers and a legend marker per group; the front's three markers carry the ring.
    EXPECT_EQ(xml.classCounts.at("point"), 4 + 2);
    EXPECT_EQ(xml.classCounts.at("group-0"), 2 + 1);
    EXPECT_EQ(xml.classCounts.at("group-1"), 2 + 1);
    EXPECT_EQ(xml.classCounts.at("pareto-point"), 3);
    EXPECT_EQ(xml.classCounts.at("legend-entry"), 2 + 1);
    EXPECT_NE(svg.find(">bilateral, sphere</text>"), std::string::npos);
    EXPECT_NE(svg.find("<title>bilateral, sphere b2"), std::string::npos);
    // Without groups the chart is a sweep's: one colour, no group classes.
    chart.groups.clear();
    const std::string plain = tc::scatterSvg(chart);
    EXPECT_EQ(plain.find("group-"), std::string::npos);
    EXPECT_EQ(twinrender::test::checkXml(plain).classCounts.count("legend-entry"), 0u);
}

TEST(ScatterSvg, NoDrawablePointsStillMakesAChart) {
    tc::ScatterChart chart;
    chart.points = {{NAN, 1.0, "a"}};
    const std::string svg = tc::scatterSvg(chart);
    const auto xml = twinrender::test::checkXml(svg);
    ASSERT_EQ(xml.error, "") << svg;
    EXPECT_EQ(xml.classCounts.at("point"), 2);  // the legend's only
    EXPECT_NE(svg.find("1 of 1 points not drawn"), std::string::npos);
}

TEST(LineSvg, OneLineAndMarkerPerSeriesOnLogAxes) {
    tc::LineChart chart;
    chart.title = "depth: id.mismatch <against> far/near";
    chart.xLabel = "far / near";
    chart.yLabel = "id.mismatch (lower is better)";
    chart.xScale = tc::AxisScale::Log;
    chart.series = {{"standard", {{1e2, 0.0, "a"}, {1e6, 0.3, ""}, {1e12, 0.4, ""}}, false},
                    {"log & co", {{1e2, 0.0, ""}, {1e6, NAN, ""}, {1e12, 0.01, ""}}, true}};
    chart.xMarks = {{1e6, "standard breaks"}};
    const std::string svg = tc::lineSvg(chart);
    const auto xml = twinrender::test::checkXml(svg);
    ASSERT_EQ(xml.error, "") << svg;
    // 5 drawable points and one legend marker per series; the NaN breaks the second line.
    EXPECT_EQ(xml.classCounts.at("point"), 5 + 2);
    EXPECT_EQ(xml.classCounts.at("series-0"), 3 + 1 + 2);  // markers, line, legend line+marker
    EXPECT_EQ(xml.classCounts.at("line"), 1 + 0 + 2);      // runs of one point draw no line
    EXPECT_EQ(xml.classCounts.at("legend-entry"), 2);
    EXPECT_EQ(xml.classCounts.at("mark"), 1);
    EXPECT_EQ(xml.classCounts.at("dashed"), 1);  // the legend's; the dashed series has no run
    EXPECT_NE(svg.find("far / near — log scale"), std::string::npos);
    EXPECT_NE(svg.find("1e+12"), std::string::npos);  // decade ticks
    EXPECT_NE(svg.find("log &amp; co"), std::string::npos);
    EXPECT_NE(svg.find("1 of 6 points not drawn"), std::string::npos);
}

TEST(LineSvg, LinearAxesStartErrorsAtZeroAndLogYDropsNonPositive) {
    tc::LineChart chart;
    chart.xLabel = "view angle (degrees)";
    chart.yLabel = "normal.mean_deg (°)";
    chart.series = {{"SSSS on", {{0, 3.0, ""}, {45, 4.0, ""}, {85, 9.0, ""}}, false}};
    std::string svg = tc::lineSvg(chart);
    ASSERT_EQ(twinrender::test::checkXml(svg).error, "");
    EXPECT_NE(svg.find(">0</text>"), std::string::npos);  // the y axis reaches 0
    EXPECT_EQ(svg.find("log scale"), std::string::npos);
    chart.yScale = tc::AxisScale::Log;
    chart.series[0].points[0].y = 0.0;
    svg = tc::lineSvg(chart);
    const auto xml = twinrender::test::checkXml(svg);
    ASSERT_EQ(xml.error, "");
    EXPECT_EQ(xml.classCounts.at("point"), 2 + 1);
    EXPECT_NE(svg.find("finite positive"), std::string::npos);
}

// The colours of a chart's series, from their <g data-colour="...">.
std::vector<std::string> seriesColours(const std::string& svg) {
    std::vector<std::string> out;
    for (std::size_t at = svg.find("data-colour=\""); at != std::string::npos;
         at = svg.find("data-colour=\"", at + 1)) {
        const std::size_t start = at + 13;
        out.push_back(svg.substr(start, svg.find('"', start) - start));
    }
    return out;
}

TEST(LineSvg, NoTwoSeriesShareAColourAndMarkersTakeTurns) {
    tc::LineChart chart;
    for (int k = 0; k < 20; ++k)
        chart.series.push_back({"method " + std::to_string(k), {{1.0, 0.1 * k, ""}}, false});
    const std::string svg = tc::lineSvg(chart);
    ASSERT_EQ(twinrender::test::checkXml(svg).error, "") << svg;
    const auto colours = seriesColours(svg);
    ASSERT_EQ(colours.size(), 20u);
    for (std::size_t a = 0; a < colours.size(); ++a)
        for (std::size_t b = a + 1; b < colours.size(); ++b)
            EXPECT_NE(colours[a], colours[b]) << a << " and " << b;
    // Circle, square, triangle, diamond in turn: a second cue beside the colour.
    const auto xml = twinrender::test::checkXml(svg);
    EXPECT_EQ(xml.elementCounts.at("rect") - 2, 5 * 2);  // background, frame; markers, legend
    EXPECT_EQ(xml.elementCounts.at("path"), 10 * 2);
}

TEST(LineSvg, TicksAtFewDataValuesOneNotationAndTheBoundDrawn) {
    tc::LineChart chart;
    chart.xScale = tc::AxisScale::Log;
    chart.series = {{"pcf", {{64, 0.5, ""}, {256, 0.3, ""}, {1024, 0.1, ""}}, false}};
    chart.yMarks = {{0.2, "max 0.2"}, {50.0, "max 50"}};
    std::string svg = tc::lineSvg(chart);
    ASSERT_EQ(twinrender::test::checkXml(svg).error, "") << svg;
    for (const char* t : {">64</text>", ">256</text>", ">1024</text>"})
        EXPECT_NE(svg.find(t), std::string::npos) << t << svg;
    EXPECT_EQ(svg.find(">100</text>"), std::string::npos);
    EXPECT_EQ(twinrender::test::checkXml(svg).classCounts.at("bound"), 1);
    EXPECT_NE(svg.find(">max 0.2</text>"), std::string::npos);
    EXPECT_NE(svg.find(">max 50: off the chart</text>"), std::string::npos);
    // Round ticks spanning 1e4 to 1e5 are all written with an exponent, or none is.
    chart = {};
    chart.series = {{"a",
                     {{0, 0, ""},
                      {1, 0, ""},
                      {2, 0, ""},
                      {3, 0, ""},
                      {4, 0, ""},
                      {5, 0, ""},
                      {6, 0, ""},
                      {7, 0, ""},
                      {8, 0, ""},
                      {120000, 0, ""}},
                     false}};
    svg = tc::lineSvg(chart);
    EXPECT_NE(svg.find(">1e+05</text>"), std::string::npos) << svg;
    EXPECT_EQ(svg.find(">50000</text>"), std::string::npos) << svg;
    EXPECT_NE(svg.find(">5e+04</text>"), std::string::npos) << svg;
}

TEST(LineSvg, LegendEntriesDoNotOverlap) {
    tc::LineChart chart;
    for (const char* n : {"narrow_range, ellipsoid, iterations 3", "ssss, sphere", "none",
                          "curvature_flow, ellipsoid, 40 steps", "bilateral", "x"})
        chart.series.push_back({n, {{1.0, 1.0, ""}}, false});
    const std::string svg = tc::lineSvg(chart);
    // Each legend text starts after the previous one on its row ends (6.5 px a character).
    double lastEnd = 0, lastY = -1;
    for (std::size_t at = svg.find("<g class=\"legend-entry\">"); at != std::string::npos;
         at = svg.find("<g class=\"legend-entry\">", at + 1)) {
        const std::size_t text = svg.find("<text class=\"label\" x=\"", at) + 23;
        const double x = std::stod(svg.substr(text));
        const double y = std::stod(svg.substr(svg.find("y=\"", text) + 3));
        const std::size_t open = svg.find('>', text) + 1;
        const std::size_t chars = svg.find("</text>", open) - open;
        if (y == lastY) {
            EXPECT_GE(x - 30, lastEnd) << svg;
        }
        lastEnd = x + 6.5 * static_cast<double>(chars);
        lastY = y;
    }
}
