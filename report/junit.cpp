#include "report/junit.h"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <vector>

#include "core/image_io.h"
#include "report/markup.h"

namespace twinrender::report {

using compare::Check;
using compare::exactValue;
using compare::Status;

namespace fs = std::filesystem;

namespace {

// One <testcase>; the texts are raw (escaped when written), the properties XML already.
struct Case {
    std::string classname, name, properties, failure, failureMessage, error, out;
};

// The testcase of one metric: its value, every bound as a property; the failing checks'
// messages as its failure, the warnings as its output.
Case metricCase(const std::string& classname, const std::string& metric,
                const std::vector<const Check*>& checks) {
    Case k{classname, metric, "", "", "", "", ""};
    k.properties += fmt::format("        <property name=\"value\" value=\"{}\"/>\n",
                                xmlEscape(exactValue(checks.front()->value), true));
    for (const Check* c : checks) {
        if (c->baseline) {
            k.properties += fmt::format(
                "        <property name=\"baseline\" value=\"{}\"/>\n"
                "        <property name=\"baseline_limit\" value=\"{}\"/>\n"
                "        <property name=\"delta\" value=\"{}\"/>\n",
                exactValue(*c->baseline), exactValue(c->limit),
                exactValue(c->value - *c->baseline));
        } else {
            k.properties += fmt::format("        <property name=\"{}\" value=\"{}\"/>\n",
                                        xmlEscape(c->bound, true), exactValue(c->limit));
        }
        if (c->status == Status::Fail) {
            if (k.failureMessage.empty()) k.failureMessage = c->message;
            k.failure += c->message + "\n";
        } else if (c->status == Status::Warn) {
            k.out += "warning: " + c->message + "\n";
        }
    }
    return k;
}

// A scene's testcases: "render" with an error, "render" without checks, else one per checked
// metric, grouped by metric in the order the checks come.
void addSceneCases(const SceneReport& scene, std::vector<Case>& cases) {
    const std::string classname = "twinrender." + scene.name;
    if (!scene.error.empty()) {
        cases.push_back({classname, "render", "", "", "", scene.error, ""});
        return;
    }
    std::vector<std::string> order;
    std::map<std::string, std::vector<const Check*>> byMetric;
    for (const Check& c : scene.checks) {
        if (!byMetric.count(c.metric)) order.push_back(c.metric);
        byMetric[c.metric].push_back(&c);
    }
    if (order.empty()) {
        cases.push_back({classname, "render", "", "", "", "", "rendered and compared; no checks"});
        return;
    }
    for (const std::string& metric : order)
        cases.push_back(metricCase(classname, metric, byMetric[metric]));
}

std::string testcaseXml(const Case& c) {
    std::string xml = fmt::format("    <testcase classname=\"{}\" name=\"{}\" time=\"0\"",
                                  xmlEscape(c.classname, true), xmlEscape(c.name, true));
    if (c.properties.empty() && c.failure.empty() && c.error.empty() && c.out.empty())
        return xml + "/>\n";
    xml += ">\n";
    if (!c.properties.empty())
        xml += "      <properties>\n" + c.properties + "      </properties>\n";
    if (!c.failure.empty())
        xml += fmt::format("      <failure message=\"{}\" type=\"threshold\">{}</failure>\n",
                           xmlEscape(c.failureMessage, true), xmlEscape(c.failure, false));
    if (!c.error.empty())
        xml += fmt::format("      <error message=\"{}\" type=\"render\">{}</error>\n",
                           xmlEscape(c.error, true), xmlEscape(c.error, false));
    if (!c.out.empty())
        xml += fmt::format("      <system-out>{}</system-out>\n", xmlEscape(c.out, false));
    return xml + "    </testcase>\n";
}

// The renders' total time, seconds: the suite's time.
double renderSeconds(const RunReport& run) {
    double seconds = 0.0;
    for (const SceneReport& scene : run.scenes)
        for (const auto& [renderer, r] : scene.renderers)
            if (auto it = r.timingsMs.find("total");
                it != r.timingsMs.end() && std::isfinite(it->second))
                seconds += it->second / 1000.0;
    return seconds;
}

}  // namespace

std::string junitXml(const RunReport& run) {
    std::vector<Case> cases;
    for (const SceneReport& scene : run.scenes) addSceneCases(scene, cases);
    std::size_t failures = 0, errors = 0;
    for (const Case& c : cases) {
        failures += !c.failure.empty();
        errors += !c.error.empty();
    }
    const double seconds = renderSeconds(run);
    std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    xml += fmt::format(
        "<testsuites name=\"twinrender\" tests=\"{}\" failures=\"{}\" errors=\"{}\" "
        "time=\"{:.3f}\">\n",
        cases.size(), failures, errors, seconds);
    xml += fmt::format(
        "  <testsuite name=\"twinrender\" tests=\"{}\" failures=\"{}\" errors=\"{}\" "
        "skipped=\"0\" time=\"{:.3f}\"{}>\n",
        cases.size(), failures, errors, seconds,
        run.createdAt.empty() ? "" : " timestamp=\"" + xmlEscape(run.createdAt, true) + "\"");
    for (const Case& c : cases) xml += testcaseXml(c);
    xml += "  </testsuite>\n</testsuites>\n";
    return xml;
}

void writeJunit(const RunReport& run, const fs::path& file) {
    core::writeTextFile(file, junitXml(run));
}

}  // namespace twinrender::report
