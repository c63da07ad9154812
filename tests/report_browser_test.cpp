// The HTML report in a real browser: Debian's headless Chromium opens the index and the scene
// pages of a small report built from synthetic images (no renderer needed) and each page's
// self-test (report/report_assets/selftest.js) must find no script error, no console.error
// and no image that failed to load. Pages with a broken image path, a script error and a
// reference to the network are opened too and must be reported as failing, so the check is
// known to be able to fail.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "report/report.h"
#include "report/report_html.h"
#include "report/testdata/synthetic_report.h"
#include "tests/cli_harness.h"

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

// Opens one page in headless Chromium with a fresh profile, lets it load (virtual time, so
// the result does not depend on the machine's speed) and returns its self-test verdict.
PageResult openPage(const std::string& chromium, const fs::path& page, const fs::path& work) {
    static int run = 0;
    const fs::path profile = work / ("profile_" + std::to_string(run++));
    fs::create_directories(profile);
    const std::string cmd =
        "timeout 120 " + shellQuote(chromium) +
        " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run"
        " --disable-background-networking --disable-component-update --disable-sync"
        " --user-data-dir=" +
        shellQuote(profile.string()) + " --virtual-time-budget=5000 --dump-dom " +
        shellQuote("file://" + page.string()) + " 2>" +
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

TEST_F(ReportInBrowser, EveryPageLoadsWithoutErrors) {
    for (const std::string page :
         {"index.html", "sphere/index.html", "sphere_shifted/index.html"}) {
        const PageResult r = openPage(chromium, report / page, work);
        ASSERT_FALSE(r.dom.empty()) << page << ": Chromium printed no DOM; its stderr:\n"
                                    << stderrTail(work);
        EXPECT_EQ(r.selftest.rfind("selftest: ok (", 0), 0u)
            << page << ": " << r.selftest << "\n(the self-test never ran if this is empty; "
            << "Chromium's stderr:\n"
            << stderrTail(work) << ")";
    }
    // The scene pages show every buffer of both renders and the ꟻLIP and HDR-ꟻLIP maps:
    // 2 x 10 + 2 panels (the synthetic frames have irradiance and in-scatter), and the two
    // images of the swap view.
    const PageResult scene = openPage(chromium, report / "sphere" / "index.html", work);
    EXPECT_NE(scene.selftest.find("(24 images)"), std::string::npos) << scene.selftest;
    // The page script ran: the buffer switch is set to the first buffer.
    EXPECT_NE(scene.dom.find("data-buffer=\"beauty\" aria-pressed=\"true\""), std::string::npos);
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

}  // namespace
