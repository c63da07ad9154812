#include "report/study_summary.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tc = twinrender::report;

namespace {

tc::StudyRow row(const std::string& scene, const std::string& series, double x, double ms,
                 double error) {
    tc::StudyRow r;
    r.scene = scene;
    r.series = series;
    r.x = x;
    r.timingsMs = {{"total", ms}, {"surface", ms / 2}};
    r.metrics = {{"normal.mean_deg", error}, {"smoothness.ratio", 1.0 + error}};
    return r;
}

}  // namespace

TEST(StudySummary, MedianOfTheFiniteValues) {
    EXPECT_DOUBLE_EQ(tc::median({3.0, 1.0, 2.0}), 2.0);
    EXPECT_DOUBLE_EQ(tc::median({4.0, 1.0, 3.0, 2.0}), 2.5);
    EXPECT_DOUBLE_EQ(tc::median({NAN, 5.0, INFINITY}), 5.0);
    EXPECT_TRUE(std::isnan(tc::median({})));
    EXPECT_TRUE(std::isnan(tc::median({NAN})));
}

TEST(StudySummary, MediansOverScenesPerSettingAndTheirFront) {
    // Three settings on three scenes (time ms, normal error):
    //   none      (10, 2.0) (20, 1.0) (30, 3.0)  -> median (20, 2.0)
    //   filter 1  (12, 1.0) (22, 0.5) (90, 9.0)  -> median (22, 1.0)
    //   filter 2  (40, 1.5) (50, 1.5) (60, 1.5)  -> median (50, 1.5): slower and worse than
    //                                               filter 1, off the front
    std::vector<tc::StudyRow> rows = {
        row("a", "none", 0, 10, 2.0),   row("a", "filter", 1, 12, 1.0),
        row("a", "filter", 2, 40, 1.5), row("b", "none", 0, 20, 1.0),
        row("b", "filter", 1, 22, 0.5), row("b", "filter", 2, 50, 1.5),
        row("c", "none", 0, 30, 3.0),   row("c", "filter", 1, 90, 9.0),
        row("c", "filter", 2, 60, 1.5), row("d", "filter", 2, 1.0, 0.0)};
    rows.back().error = "failed";  // takes no part
    std::vector<const tc::StudyRow*> ptrs;
    for (const auto& r : rows) ptrs.push_back(&r);
    const auto settings = tc::mediansOverScenes(ptrs);
    ASSERT_EQ(settings.size(), 3u);
    EXPECT_EQ(settings[0].series, "none");
    EXPECT_EQ(settings[1].x, 1.0);
    EXPECT_EQ(settings[2].scenes, (std::vector<std::string>{"a", "b", "c"}));
    EXPECT_DOUBLE_EQ(settings[0].timingsMs.at("total"), 20.0);
    EXPECT_DOUBLE_EQ(settings[0].timingsMs.at("surface"), 10.0);
    EXPECT_DOUBLE_EQ(settings[0].metrics.at("normal.mean_deg"), 2.0);
    EXPECT_DOUBLE_EQ(settings[1].timingsMs.at("total"), 22.0);
    EXPECT_DOUBLE_EQ(settings[1].metrics.at("normal.mean_deg"), 1.0);
    EXPECT_DOUBLE_EQ(settings[2].metrics.at("normal.mean_deg"), 1.5);
    EXPECT_EQ(tc::settingsFront(settings, "normal.mean_deg"), (std::vector<std::size_t>{0, 1}));
    // smoothness.ratio is best at 1: the front takes the distance to it (the same order here).
    EXPECT_EQ(tc::settingsFront(settings, "smoothness.ratio"), (std::vector<std::size_t>{0, 1}));
    // A faster setting that is no better joins the front at its own end.
    rows.push_back(row("a", "fast", 0, 1, 5.0));
    ptrs.clear();
    for (const auto& r : rows) ptrs.push_back(&r);
    const auto more = tc::mediansOverScenes(ptrs);
    EXPECT_EQ(tc::settingsFront(more, "normal.mean_deg"), (std::vector<std::size_t>{3, 0, 1}));
}
