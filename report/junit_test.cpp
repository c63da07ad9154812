#include "report/junit.h"

#include <gtest/gtest.h>

#include "report/testdata/synthetic_report.h"

namespace twinrender::report {
namespace {

using namespace twinrender::compare;  // what the report shows

using testdata::sceneWithChecks;

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + what.size()))
        ++n;
    return n;
}

TEST(ReportJunit, OneTestcasePerSceneAndCheckedMetric) {
    RunReport run;
    run.scenes.push_back(sceneWithChecks());
    SceneReport ok;
    ok.name = "contact";
    run.scenes.push_back(ok);
    SceneReport broken;
    broken.name = "ring<world>";
    broken.error = "no \"GL\" & no luck";
    run.scenes.push_back(broken);
    const std::string xml = junitXml(run);
    EXPECT_EQ(xml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>", 0), 0u);
    EXPECT_EQ(count(xml, "<testsuite "), 1u);
    EXPECT_EQ(count(xml, "</testsuite>"), 1u);
    // planet: beauty.flip, coverage.iou, shadow.iou; contact: render; ring<world>: render.
    EXPECT_EQ(count(xml, "<testcase "), 5u);
    EXPECT_EQ(count(xml, "<failure "), 2u);  // beauty.flip (max and baseline), coverage.iou
    EXPECT_EQ(count(xml, "<error "), 1u);
    EXPECT_EQ(count(xml, "<system-out>"), 2u);  // shadow.iou's warning, contact's note
    EXPECT_NE(xml.find("tests=\"5\" failures=\"2\" errors=\"1\""), std::string::npos) << xml;
    EXPECT_NE(xml.find("<testcase classname=\"twinrender.planet\" name=\"beauty.flip\""),
              std::string::npos);
    EXPECT_NE(xml.find("<property name=\"value\" value=\"0.2\"/>"), std::string::npos) << xml;
    EXPECT_NE(xml.find("<property name=\"max\" value=\"0.15\"/>"), std::string::npos) << xml;
    EXPECT_NE(xml.find("<property name=\"baseline\" value=\"0.1\"/>"), std::string::npos) << xml;
    EXPECT_NE(
        xml.find("<failure message=\"beauty.flip = 0.2 is above its max 0.15 (t.toml:1:25)\""),
        std::string::npos)
        << xml;
    EXPECT_NE(xml.find("beauty.flip got worse than the baseline: 0.1 -&gt; 0.2"), std::string::npos)
        << xml;
    EXPECT_NE(xml.find("warning: shadow.iou = 0.97 is below its warn_min 0.98"), std::string::npos)
        << xml;
    EXPECT_NE(xml.find("classname=\"twinrender.ring&lt;world&gt;\""), std::string::npos) << xml;
    EXPECT_NE(xml.find("message=\"no &quot;GL&quot; &amp; no luck\""), std::string::npos) << xml;
    // Every element opened is closed.
    EXPECT_EQ(count(xml, "<testcase "), count(xml, "</testcase>") + count(xml, "\"0\"/>"));
    EXPECT_EQ(count(xml, "<properties>"), count(xml, "</properties>"));
}

}  // namespace
}  // namespace twinrender::report
