#include "report/scene_facts.h"

#include <fmt/format.h>

#include <cmath>

#include "compare/thresholds.h"
#include "core/device_name.h"
#include "report/markup.h"

namespace twinrender::report {

using compare::Check;
using compare::formatValue;
using compare::Status;
using compare::toString;
using compare::worst;

namespace fs = std::filesystem;

namespace {

// The program an external renderer's command runs: its script where an interpreter runs one
// ("python3 examples/vtk_fluid/render.py --x" -> "render.py"), else the executable's name.
std::string programName(const std::string& command) {
    std::vector<std::string> words;
    std::string word;
    for (char c : command + ' ') {
        if (c != ' ') {
            word += c;
        } else if (!word.empty()) {
            words.push_back(word);
            word.clear();
        }
    }
    auto base = [](const std::string& w) { return fs::path(w).filename().string(); };
    for (const std::string& w : words) {
        const std::string b = base(w);
        const bool interpreter = b == "env" || b.starts_with("python") || b == "sh" ||
                                 b == "bash" || b == "node" || b == "perl" || b == "ruby";
        if (!interpreter && !w.starts_with("-")) return b;
    }
    return words.empty() ? "" : base(words.front());
}

}  // namespace

std::string testRenderer(const SceneReport& s) {
    if (s.renderers.count("realtime")) return "realtime";
    for (const auto& [name, r] : s.renderers)
        if (name != "raymarch") return name;
    return "realtime";
}

std::vector<std::string> renderersOf(const SceneReport& s) {
    return {testRenderer(s), "raymarch"};
}

std::string rendererLabel(const SceneReport& s, const std::string& renderer) {
    if (renderer == "realtime") return "Real-time";
    if (renderer == "raymarch") return "Reference";
    if (renderer == "external") {
        const std::string device = deviceOf(s, renderer);
        const std::string prefix = "external: ";
        const std::string program =
            device.starts_with(prefix) ? programName(device.substr(prefix.size())) : "";
        return program.empty() ? "External renderer" : "External: " + program;
    }
    return renderer;
}

std::string runTestLabel(const RunReport& run) {
    std::string label;
    for (const SceneReport& s : run.scenes) {
        const std::string l = rendererLabel(s, testRenderer(s));
        if (!label.empty() && l != label) return "Test renderer";
        label = l;
    }
    return label.empty() ? "Real-time" : label;
}

std::optional<double> sceneTimeMs(const SceneReport& s, const std::string& renderer) {
    if (auto m = s.metrics.find("time." + renderer + "_ms"); m != s.metrics.end()) return m->second;
    auto r = s.renderers.find(renderer);
    if (r == s.renderers.end()) return std::nullopt;
    auto t = r->second.timingsMs.find("total");
    if (t == r->second.timingsMs.end()) return std::nullopt;
    return t->second;
}

std::string formatMs(double ms) {
    if (!std::isfinite(ms)) return formatValue(ms);
    if (ms < 1.0) return fmt::format("{:.2f} ms", ms);
    if (ms < 1000.0) return fmt::format("{:.1f} ms", ms);
    if (ms < 60000.0) return fmt::format("{:.2f} s", ms / 1000.0);
    return fmt::format("{:.0f} min {:.0f} s", std::floor(ms / 60000.0),
                       std::fmod(ms, 60000.0) / 1000.0);
}

std::string speedRatio(const SceneReport& s) {
    auto rt = sceneTimeMs(s, testRenderer(s)), ref = sceneTimeMs(s, "raymarch");
    if (!rt || !ref || !(*rt > 0.0) || !std::isfinite(*ref)) return "";
    const double r = *ref / *rt;
    return r >= 100  ? fmt::format("{:.0f}×", r)
           : r >= 10 ? fmt::format("{:.1f}×", r)
                     : fmt::format("{:.2f}×", r);
}

std::string timeBasis(const SceneReport& s) {
    if (!s.sequence || s.sequence->frames.size() < 2) return "";
    return fmt::format("median of {} frames", s.sequence->frames.size());
}

std::string deviceOf(const SceneReport& s, const std::string& renderer) {
    const auto r = s.renderers.find(renderer);
    return r == s.renderers.end() ? "" : r->second.device;
}

bool ranOnSoftwareRasteriser(const SceneReport& s) {
    return testRenderer(s) == "realtime" && core::isSoftwareRasteriser(deviceOf(s, "realtime"));
}

std::string softwareRasteriserNote(const std::string& device) {
    return "<p class=\"device-note\">The real-time renderer ran on <b>" + htmlEscape(device) +
           "</b>, a software rasteriser: the CPU drew every frame, so its times are far from a "
           "GPU's and a speed-up below 1× is expected here. The images and their errors are "
           "the same on a GPU (<code>--require-gpu</code> refuses a software "
           "rasteriser).</p>\n";
}

bool isNotApplicable(const SceneReport& s, const std::string& metric) {
    return s.notApplicable.count(metric) > 0;
}

std::optional<Status> metricStatus(const SceneReport& s, const std::string& metric) {
    std::optional<Status> st;
    for (const Check& c : s.checks)
        if (c.metric == metric) st = st ? worst(*st, c.status) : c.status;
    return st;
}

std::string valueCell(const SceneReport& s, const std::string& metric,
                      const std::string& thresholdsFile) {
    if (const auto na = s.notApplicable.find(metric); na != s.notApplicable.end())
        return "<td class=\"num muted\" title=\"not applicable: " + htmlEscape(na->second) +
               "\">n/a</td>";
    auto st = metricStatus(s, metric);
    auto it = s.metrics.find(metric);
    const std::string text = it == s.metrics.end() ? "—" : formatValue(it->second);
    std::string title;
    for (const Check& c : s.checks)
        if (c.metric == metric) title += (title.empty() ? "" : "\n") + c.message;
    if (title.empty() && it != s.metrics.end() && !thresholdsFile.empty())
        title = fmt::format("no bound: {} sets none for this metric on this scene", thresholdsFile);
    return fmt::format(
        "<td class=\"num{}{}\"{}>{}</td>", st ? " " : "", st ? toString(*st) : std::string_view(),
        title.empty() ? "" : fmt::format(" title=\"{}\"", htmlEscape(title)), htmlEscape(text));
}

std::string countsText(const std::vector<Status>& statuses, std::string_view noun) {
    int n[3] = {0, 0, 0};
    for (Status s : statuses) ++n[static_cast<int>(s)];
    std::string t = fmt::format("{} {}{}", statuses.size(), noun, statuses.size() == 1 ? "" : "s");
    t += fmt::format(": {} pass", n[0]);
    if (n[1]) t += fmt::format(", {} warn", n[1]);
    if (n[2]) t += fmt::format(", {} fail", n[2]);
    return t;
}

std::vector<std::pair<Status, std::string>> problemsOf(const SceneReport& s) {
    std::vector<std::pair<Status, std::string>> problems;
    if (!s.error.empty()) problems.emplace_back(Status::Fail, s.error);
    for (Status want : {Status::Fail, Status::Warn})
        for (const Check& c : s.checks)
            if (c.status == want) problems.emplace_back(want, c.message);
    return problems;
}

std::vector<std::pair<std::string, std::string>> rawFiles(const SceneReport& s) {
    std::vector<std::pair<std::string, std::string>> files;
    for (const std::string& r : renderersOf(s)) {
        const auto it = s.renderers.find(r);
        if (it == s.renderers.end()) continue;
        // Beside the renderer's beauty PNG, as the commands that render write them: its AOV
        // image and its frame's JSON.
        const auto beauty = it->second.images.find("beauty");
        if (beauty == it->second.images.end()) continue;
        const fs::path folder = fs::path(beauty->second).parent_path();
        for (const char* ext : {".exr", ".json"}) {
            const std::string path = (folder / (r + ext)).generic_string();
            files.emplace_back(path, path);
        }
    }
    files.emplace_back("metrics.json", "metrics.json");
    if (s.sequence)
        for (const auto& [type, file] : s.sequence->videos) files.emplace_back(file, file);
    return files;
}

}  // namespace twinrender::report
