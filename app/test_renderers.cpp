#include "app/test_renderers.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <utility>

#include "core/error.h"

namespace twinrender::app {

namespace {

// A renderer's results from its own report of the scene; image paths made relative to the
// scene's folder.
report::TestRendererReport resultsOf(report::SceneReport& r, const std::string& name,
                                     const std::string& folder) {
    report::TestRendererReport t{.name = name,
                                 .metrics = r.metrics,
                                 .notProvided = r.notProvided,
                                 .checks = r.checks,
                                 .error = r.error,
                                 .render = {}};
    for (auto& [renderer, rr] : r.renderers)
        if (renderer != "raymarch") t.render = rr;
    for (auto& [buffer, path] : t.render.images) path = folder + path;
    return t;
}

}  // namespace

TestRendererSpec parseTestRenderer(const std::string& spec) {
    const auto colon = spec.find(':');
    TestRendererSpec t{.name = spec, .renderer = spec.substr(0, colon), .overrides = {}};
    if (t.renderer != "realtime" && t.renderer != "external" && t.renderer != "images")
        throw core::InputError(
            fmt::format("--test {}: no such test renderer; the test renderers are realtime, "
                        "realtime:KEY=VALUE[,KEY=VALUE...] and external",
                        spec));
    if (colon == std::string::npos) return t;
    if (t.renderer != "realtime")
        throw core::InputError(fmt::format(
            "--test {}: only the built-in renderer takes settings (realtime:KEY=VALUE,...)", spec));
    for (std::size_t start = colon + 1;;) {
        const auto comma = spec.find(',', start);
        const std::string set = spec.substr(start, comma - start);
        if (set.rfind("realtime.", 0) != 0 || set.find('=') == std::string::npos)
            throw core::InputError(fmt::format(
                "--test {}: '{}' is not a realtime.KEY=VALUE setting (every test renderer is "
                "measured against the same reference, so only the real-time renderer's keys "
                "may differ)",
                spec, set));
        t.overrides.push_back(set);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return t;
}

std::string testRendererFolder(const std::vector<std::string>& names, std::size_t k) {
    if (k == 0) return "";
    std::string folder = names.at(k);
    for (char& c : folder)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_')
            c = '_';
    return "tests/" + folder + "/";
}

report::SceneReport joinTestRenderers(std::vector<report::SceneReport> reports,
                                      const std::vector<std::string>& names) {
    report::SceneReport scene = std::move(reports.at(0));
    if (reports.size() == 1) return scene;
    scene.tests.push_back(resultsOf(scene, names[0], ""));
    for (std::size_t k = 1; k < reports.size(); ++k) {
        const std::string& name = names.at(k);
        report::TestRendererReport t = resultsOf(reports[k], name, testRendererFolder(names, k));
        for (const compare::Check& c : t.checks) {
            if (c.status == compare::Status::Pass) continue;
            compare::Check named = c;
            named.metric = name + ":" + c.metric;
            named.message = name + ": " + c.message;
            scene.checks.push_back(std::move(named));
        }
        if (!t.error.empty())
            scene.checks.push_back({.metric = name + ":render",
                                    .value = NAN,
                                    .bound = "render",
                                    .limit = NAN,
                                    .status = compare::Status::Fail,
                                    .message = name + ": " + t.error,
                                    .where = {},
                                    .baseline = {}});
        scene.tests.push_back(std::move(t));
    }
    return scene;
}

}  // namespace twinrender::app
