// The HTML report in a real browser: Debian's headless Chromium opens the index and the scene
// pages of a small report built from synthetic images (no renderer needed) and each page's
// self-test (report/report_assets/selftest.js) must find no script error, no console.error,
// no image that failed to load and, at window widths of 1280 and 1920 px, no page and no
// index table wider than its box; every link of the pages Chromium loaded must name a file
// that exists; and charts drawn in the browser must give no two series one colour. Pages with
// a broken image path, a script error, a reference to the network, an overflowing table, a
// broken link and two series of one colour are checked too and must be reported as failing,
// so each check is known to be able to fail.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "report/markup.h"
#include "report/report.h"
#include "report/report_html.h"
#include "report/svg_chart.h"
#include "report/testdata/synthetic_report.h"
#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::report_browser_test {

namespace {

namespace fs = std::filesystem;
namespace tc = twinrender::report;
namespace tt = twinrender::test;
using tt::readText;

// $TWINRENDER_CHROMIUM, else Debian's /usr/bin/chromium; empty when neither exists.
std::string findChromium() {
    if (const char* env = std::getenv("TWINRENDER_CHROMIUM"); env && fs::exists(env)) return env;
    for (const char* p : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
        if (fs::exists(p)) return p;
    return "";
}

std::string shellQuote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

struct PageResult {
    std::string selftest;  // the text of <pre id="selftest">, as dumped (HTML-escaped)
    std::string dom;       // the whole dump, for failure messages
};

// Opens one page in headless Chromium (scripts/headless-chromium) with a fresh profile in a
// window `width` px wide, lets it load (virtual time, so the result does not depend on the
// machine's speed) and returns its self-test verdict.
PageResult openPage(const std::string& chromium, const fs::path& page, const fs::path& work,
                    int width = 1280) {
    static int run = 0;
    const fs::path profile = work / ("profile_" + std::to_string(run++));
    fs::create_directories(profile);
    // scripts/headless-chromium: the flags scripts/report-pictures photographs the report with.
    const std::string cmd =
        "TWINRENDER_CHROMIUM=" + shellQuote(chromium) + " " +
        shellQuote(
            (::twinrender::testing::sourceDir() / "scripts" / "headless-chromium").string()) +
        " " + std::to_string(width) + " 900 " + shellQuote(profile.string()) + " " +
        shellQuote("file://" + page.string()) + " --dump-dom 2>" +
        shellQuote((work / "chromium_stderr.txt").string());
    PageResult r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf{};
    while (std::size_t n = std::fread(buf.data(), 1, buf.size(), pipe)) r.dom.append(buf.data(), n);
    pclose(pipe);
    const auto open = r.dom.find("<pre id=\"selftest\"");
    if (open == std::string::npos) return r;
    const auto start = r.dom.find('>', open);
    const auto end = r.dom.find("</pre>", start);
    if (start != std::string::npos && end != std::string::npos)
        r.selftest = r.dom.substr(start + 1, end - start - 1);
    return r;
}

// The text of the element with id `id` in a dumped DOM; "" without one.
std::string elementText(const std::string& dom, const std::string& id) {
    const auto open = dom.find("id=\"" + id + "\"");
    if (open == std::string::npos) return "";
    const auto start = dom.find('>', open);
    const auto end = dom.find("</", start);
    return start == std::string::npos || end == std::string::npos
               ? ""
               : dom.substr(start + 1, end - start - 1);
}

// The links of a dumped page that name no file: every href but fragments and data: URLs,
// resolved against the page's folder (the report links nothing else; a network URL is the
// self-test's to report).
std::vector<std::string> brokenLinks(const std::string& dom, const fs::path& page) {
    std::vector<std::string> broken;
    const std::regex href("\\shref=\"([^\"]*)\"");
    for (auto it = std::sregex_iterator(dom.begin(), dom.end(), href); it != std::sregex_iterator();
         ++it) {
        std::string target = (*it)[1];
        if (target.empty() || target[0] == '#' || target.rfind("data:", 0) == 0) continue;
        if (target.find("://") != std::string::npos) {
            broken.push_back(target);
            continue;
        }
        target = target.substr(0, target.find_first_of("#?"));
        for (std::size_t a; (a = target.find("&amp;")) != std::string::npos;)
            target.replace(a, 5, "&");
        if (!fs::exists(page.parent_path() / tc::pathOfUrl(target))) broken.push_back(target);
    }
    return broken;
}

std::string stderrTail(const fs::path& work) {
    const std::string all = readText(work / "chromium_stderr.txt");
    return all.size() > 2000 ? all.substr(all.size() - 2000) : all;
}

class ReportInBrowser : public ::testing::Test {
  protected:
    void SetUp() override {
        chromium = findChromium();
        if (chromium.empty())
            GTEST_SKIP() << "Chromium is not installed, so the report cannot be tested in a "
                            "browser; install it with `apt-get install -y chromium` (scripts/setup "
                            "installs it), or point TWINRENDER_CHROMIUM at a Chromium binary";
        // One folder per test: ctest runs the tests of this suite in parallel processes.
        work = tt::freshDir(std::string("report_browser_") +
                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        report = work / "report";
        run = tc::testdata::syntheticReport(report);
        tc::writeReport(run, report);
    }

    std::string chromium;
    fs::path work, report;
    tc::RunReport run;
};

// In a 1280 px window: the self-test also fails a page wider than its window and an index
// table wider than its page.
TEST_F(ReportInBrowser, EveryPageLoadsWithoutErrorsAndEveryLinkResolves) {
    std::string scene;  // the sphere's page as Chromium left it
    for (const std::string page :
         {"index.html", "sphere/index.html", "sphere_shifted/index.html"}) {
        const PageResult r = openPage(chromium, report / page, work);
        ASSERT_FALSE(r.dom.empty()) << page << ": Chromium printed no DOM; its stderr:\n"
                                    << stderrTail(work);
        EXPECT_EQ(r.selftest.rfind("selftest: ok (", 0), 0u)
            << page << ": " << r.selftest << "\n(the self-test never ran if this is empty; "
            << "Chromium's stderr:\n"
            << stderrTail(work) << ")";
        const auto broken = brokenLinks(r.dom, report / page);
        EXPECT_TRUE(broken.empty()) << page << ": " << broken.size() << " broken, the first "
                                    << (broken.empty() ? "" : broken.front());
        if (page == "sphere/index.html") scene = r.dom;
    }
    // The scene pages show every buffer of both renders and the ꟻLIP and HDR-ꟻLIP maps:
    // 2 x 10 + 2 panels (the synthetic frames have irradiance and in-scatter), and the two
    // images of the swap view; they link their raw files.
    EXPECT_NE(scene.find("(24 images)"), std::string::npos) << scene;
    EXPECT_NE(scene.find("href=\"realtime.exr\""), std::string::npos);
    EXPECT_NE(scene.find("href=\"metrics.json\""), std::string::npos);
    // The page script ran: the buffer switch is set to the first buffer.
    EXPECT_NE(scene.find("data-buffer=\"beauty\" aria-pressed=\"true\""), std::string::npos);
}

TEST_F(ReportInBrowser, ABrokenImagePathFails) {
    // A report whose scene names an image that was never written.
    tc::RunReport broken = run;
    broken.scenes.resize(1);
    broken.scenes[0].renderers["realtime"].images["normal"] = "no_such_image.png";
    const fs::path dir = work / "broken";
    fs::create_directories(dir);
    fs::copy(report / "sphere", dir / "sphere", fs::copy_options::recursive);
    tc::writeHtmlReport(broken, dir);
    const PageResult r = openPage(chromium, dir / "sphere" / "index.html", work);
    ASSERT_FALSE(r.dom.empty()) << stderrTail(work);
    EXPECT_EQ(r.selftest.rfind("selftest: FAIL", 0), 0u) << r.selftest;
    EXPECT_NE(r.selftest.find("no_such_image.png"), std::string::npos) << r.selftest;
    // The index, whose images all exist, still passes.
    EXPECT_EQ(openPage(chromium, dir / "index.html", work).selftest.rfind("selftest: ok", 0), 0u);
}

TEST_F(ReportInBrowser, AScriptErrorAConsoleErrorAndANetworkReferenceFail) {
    const std::string page = readText(report / "sphere" / "index.html");
    const auto body = page.rfind("</body>");
    ASSERT_NE(body, std::string::npos);
    struct Case {
        const char* name;
        const char* inject;
        const char* expect;
    };
    for (const Case& c : {Case{"script_error", "<script>notAFunction();</script>", "script error"},
                          Case{"console_error", "<script>console.error('bad state');</script>",
                               "console.error: bad state"},
                          Case{"network", "<img src=\"http://example.invalid/x.png\" alt=\"\">",
                               "http://example.invalid/x.png"}}) {
        const fs::path file = report / "sphere" / (std::string(c.name) + ".html");
        std::ofstream(file) << page.substr(0, body) << c.inject << page.substr(body);
        const PageResult r = openPage(chromium, file, work);
        ASSERT_FALSE(r.dom.empty()) << c.name << ": " << stderrTail(work);
        EXPECT_EQ(r.selftest.rfind("selftest: FAIL", 0), 0u) << c.name << ": " << r.selftest;
        EXPECT_NE(r.selftest.find(c.expect), std::string::npos) << c.name << ": " << r.selftest;
    }
}

// At 1280 px EveryPageLoadsWithoutErrorsAndEveryLinkResolves holds the index to its width (the
// self-test fails a table marked data-fit wider than its box); here the wide window.
TEST_F(ReportInBrowser, TheIndexFitsItsPageAt1920PxToo) {
    const PageResult r = openPage(chromium, report / "index.html", work, 1920);
    ASSERT_FALSE(r.dom.empty()) << stderrTail(work);
    EXPECT_EQ(r.selftest.rfind("selftest: ok (", 0), 0u) << r.selftest;
}

TEST_F(ReportInBrowser, AnOverflowingTableAndABrokenLinkFail) {
    const std::string page = readText(report / "index.html");
    const auto body = page.rfind("</body>");
    ASSERT_NE(body, std::string::npos);
    const fs::path file = report / "overflow.html";
    std::ofstream(file) << page.substr(0, body)
                        << "<div><table id=\"wide\" data-fit style=\"width:3000px\"><tr><td>"
                           "x</td></tr></table></div><a href=\"no_such_page.html\">x</a>"
                        << page.substr(body);
    const PageResult r = openPage(chromium, file, work, 1280);
    ASSERT_FALSE(r.dom.empty()) << stderrTail(work);
    EXPECT_EQ(r.selftest.rfind("selftest: FAIL", 0), 0u) << r.selftest;
    EXPECT_NE(r.selftest.find("table #wide overflows its page: 3000 px"), std::string::npos)
        << r.selftest;
    EXPECT_NE(r.selftest.find("the page overflows its window"), std::string::npos) << r.selftest;
    EXPECT_EQ(brokenLinks(r.dom, file), std::vector<std::string>{"no_such_page.html"});
}

// Charts drawn inline, each in a shadow root of its own (so each keeps its own style sheet);
// the script writes into <pre id="colours"> "ok (N charts)", or "FAIL" and each pair of a
// chart's series or groups whose markers the browser fills with one colour.
std::string colourCheckPage(const std::vector<std::pair<std::string, std::string>>& charts) {
    std::string h = "<!DOCTYPE html><html><body>";
    for (const auto& [id, svg] : charts)
        h += "<template class=\"chart\" id=\"" + id + "\">" + svg.substr(svg.find("<svg")) +
             "</template>";
    h += R"js(<pre id="colours">pending</pre><script>
var problems = [], charts = document.querySelectorAll("template.chart");
charts.forEach(function (t) {
  var host = document.createElement("div");
  document.body.appendChild(host);
  var root = host.attachShadow({mode: "open"});
  root.innerHTML = t.innerHTML;
  var colourOf = {};
  root.querySelectorAll(".point").forEach(function (m) {
    var g = m.closest("g.series"), cls = m.getAttribute("class");
    var key = g ? "series '" + g.getAttribute("data-series") + "'"
                : (cls.match(/group-[0-9]+/) || [null])[0];
    if (key && !(key in colourOf) && !m.closest(".legend")) colourOf[key] = getComputedStyle(m).fill;
  });
  var byColour = {};
  for (var k in colourOf) (byColour[colourOf[k]] = byColour[colourOf[k]] || []).push(k);
  for (var c in byColour)
    if (byColour[c].length > 1) problems.push(t.id + ": " + byColour[c].join(" and ") + " share " + c);
});
document.getElementById("colours").textContent =
  problems.length ? "FAIL\n" + problems.join("\n") : "ok (" + charts.length + " charts)";
</script></body></html>)js";
    return h;
}

TEST_F(ReportInBrowser, NoTwoChartSeriesShareAColour) {
    // As many series as the methods study draws, and as many groups in a scatter.
    tc::LineChart line;
    tc::ScatterChart scatter;
    for (int k = 0; k < 16; ++k) {
        const std::string name = "method " + std::to_string(k);
        line.series.push_back({name, {{1.0, 0.1 * k, ""}, {2.0, 0.1 * k + 0.05, ""}}, false});
        scatter.points.push_back({1.0 + k, 0.5 - 0.01 * k, ""});
        scatter.groups.push_back(name);
    }
    // The check fails on two series of one colour (series 1's rule given series 0's colour).
    std::string twins = tc::lineSvg(line);
    const std::string rule = ".series-1.point{fill:";
    const auto at = twins.find(rule) + rule.size();
    twins.replace(at, 7, twins.substr(twins.find(".series-0.point{fill:") + rule.size(), 7));
    const fs::path page = work / "colours.html";
    std::ofstream(page) << colourCheckPage(
        {{"line", tc::lineSvg(line)}, {"scatter", tc::scatterSvg(scatter)}, {"twins", twins}});
    const PageResult r = openPage(chromium, page, work);
    const std::string verdict = elementText(r.dom, "colours");
    ASSERT_EQ(verdict.rfind("FAIL", 0), 0u) << verdict << stderrTail(work);
    // Only the hand-made twins share one.
    EXPECT_NE(verdict.find("twins: series 'method 0' and series 'method 1' share"),
              std::string::npos)
        << verdict;
    EXPECT_EQ(verdict.find("line:"), std::string::npos) << verdict;
    EXPECT_EQ(verdict.find("scatter:"), std::string::npos) << verdict;
}

}  // namespace

}  // namespace twinrender::e2e::report_browser_test
