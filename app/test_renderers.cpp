#include "app/test_renderers.h"

#include <cmath>
#include <utility>

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

std::string testRendererFolder(const std::vector<std::string>& names, std::size_t k) {
    return k == 0 ? "" : "tests/" + names.at(k) + "/";
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
