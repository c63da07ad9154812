#include "report/html_page.h"

#include <gtest/gtest.h>

namespace twinrender::report {
namespace {

using namespace twinrender::compare;  // what the report shows

TEST(HtmlPage, MetricHeadersShowUnitAndMeaning) {
    EXPECT_EQ(metricHeaderCell("normal.mean_deg"),
              "<th class=\"num\" title=\"mean angle between the two normals on interior pixels "
              "of the same body (lower is better)\"><span class=\"mono\">normal.mean_deg</span> "
              "<span class=\"unit\">°</span></th>");
    EXPECT_NE(metricTitle("smoothness.ratio").find("(closest to 1 is best)"), std::string::npos);
    EXPECT_NE(metricTitle("time.realtime_ms").find("(lower is better)"), std::string::npos);
    EXPECT_EQ(metricHeaderCell("x.y<z>"),
              "<th class=\"num\"><span class=\"mono\">x.y&lt;z&gt;</span></th>");
}

TEST(HtmlPage, HeaderFactsAndFooter) {
    const std::string h = pageHeader("a <b>", Status::Warn, {"one", "<code>two</code>"},
                                     "<a class=\"back\" href=\"../index.html\">back</a>");
    EXPECT_EQ(h,
              "<header class=\"top\">\n<a class=\"back\" href=\"../index.html\">back</a>\n"
              "<h1>a &lt;b&gt;</h1> <span class=\"badge warn\">warn</span>\n"
              "<div class=\"facts\"><span>one</span><span><code>two</code></span></div>\n"
              "</header>\n<main>\n");
    EXPECT_EQ(pageHeader("t", std::nullopt, {}),
              "<header class=\"top\">\n<h1>t</h1>\n<div class=\"facts\"></div>\n</header>\n"
              "<main>\n");
    const std::string page = reportPage("t", "<main></main>\n", "", "twinrender run <x>");
    EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_NE(page.find("Reproduce with <code>twinrender run &lt;x&gt;</code>."),
              std::string::npos);
    EXPECT_NE(page.find("<pre id=\"selftest\""), std::string::npos);
    EXPECT_EQ(page.find("</script>\n</body>\n</html>\n") + 26, page.size());
}

TEST(HtmlPage, ValueCellsAndErrorRows) {
    const MetricValues m = {{"beauty.flip", 0.123456}};
    EXPECT_EQ(metricValueCell(m, "beauty.flip", true), "<td class=\"num pass\">0.1235</td>");
    EXPECT_EQ(metricValueCell(m, "beauty.ssim", false), "<td class=\"num\">—</td>");
    // A check's status colours the cell, over the chart column's mark.
    EXPECT_EQ(metricValueCell(m, "beauty.flip", true, Status::Fail),
              "<td class=\"num fail\">0.1235</td>");
    EXPECT_EQ(errorRow(3, "no <GL>"),
              "<tr class=\"problems\"><td></td><td colspan=\"3\"><ul><li class=\"fail\">no "
              "&lt;GL&gt;</li></ul></td></tr>\n");
}

}  // namespace
}  // namespace twinrender::report
