#include "report/report_html.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "compare/baseline.h"
#include "compare/colour_map.h"
#include "compare/metric_table.h"
#include "compare/settings_keys.h"
#include "core/image_io.h"
#include "core/stage_table.h"
#include "core/write_roots.h"
#include "report/buffer_display.h"
#include "report/error_split_view.h"
#include "report/html_page.h"
#include "report/index_page.h"
#include "report/markup.h"
#include "report/scene_facts.h"
#include "report/sequence_report.h"
#include "report/test_renderers_section.h"

namespace twinrender::report {

using compare::BaselinePolicy;
using compare::Better;
using compare::changeText;
using compare::Check;
using compare::defaultPolicy;
using compare::ErrorMapImage;
using compare::flattenSettings;
using compare::formatValue;
using compare::inMetricOrder;
using compare::magmaCssGradient;
using compare::metricTable;
using compare::metricUnit;
using compare::Status;
using compare::toString;

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Metrics of a scene with their values, and the checked ones that are missing, in order.
std::vector<std::string> sceneMetricNames(const SceneReport& s) {
    std::vector<std::string> names;
    for (const auto& [k, v] : s.metrics) names.push_back(k);
    for (const Check& c : s.checks)
        if (!s.metrics.count(c.metric) &&
            std::find(names.begin(), names.end(), c.metric) == names.end())
            names.push_back(c.metric);
    return inMetricOrder(std::move(names));
}

// ---- scene page: metrics, timings, devices, settings ---------------------------------------

std::string boundsText(const std::vector<const Check*>& checks, bool warn) {
    std::optional<double> lo, hi;
    for (const Check* c : checks) {
        if (c->bound == (warn ? "warn_min" : "min")) lo = c->limit;
        if (c->bound == (warn ? "warn_max" : "max")) hi = c->limit;
    }
    if (lo && hi) return formatValue(*lo) + " … " + formatValue(*hi);
    if (lo) return "≥ " + formatValue(*lo);
    if (hi) return "≤ " + formatValue(*hi);
    return "";
}

// The baseline and the delta cells of a metric, the delta coloured by whether it got better
// or worse.
std::string baselineCells(const SceneReport& s, const std::string& m,
                          const std::vector<const Check*>& checks) {
    std::optional<double> base;
    if (auto b = s.baseline.find(m); b != s.baseline.end()) base = b->second;
    for (const Check* c : checks)
        if (c->baseline) base = *c->baseline;
    std::string delta;
    auto it = s.metrics.find(m);
    if (base && it != s.metrics.end()) {
        const double d = it->second - *base;
        const BaselinePolicy p = defaultPolicy(m);
        const double worsening = p.better == Better::Higher ? -d
                                 : p.better == Better::Lower
                                     ? d
                                     : std::abs(it->second - p.origin) - std::abs(*base - p.origin);
        const char* cls = worsening > 0 ? "delta-worse" : worsening < 0 ? "delta-better" : "";
        delta = fmt::format("<span class=\"{}\">{}</span>", cls,
                            htmlEscape(changeText(it->second, *base)));
    }
    return "<td class=\"num\">" + (base ? htmlEscape(formatValue(*base)) : std::string("—")) +
           "</td><td class=\"num\">" + (delta.empty() ? std::string("—") : delta) + "</td>";
}

std::string metricTable(const SceneReport& s, const std::string& thresholdsFile) {
    const bool hasBaseline =
        !s.baseline.empty() || std::any_of(s.checks.begin(), s.checks.end(),
                                           [](const Check& c) { return c.baseline.has_value(); });
    std::string h =
        "<div class=\"scroll\"><table class=\"metrics\">\n<thead><tr><th>Metric</th>"
        "<th class=\"num\">Value</th><th>Unit</th><th class=\"num\">Fail unless</th>"
        "<th class=\"num\">Warn unless</th>";
    if (hasBaseline) h += "<th class=\"num\">Baseline</th><th class=\"num\">Δ</th>";
    h += "<th>Status</th></tr></thead>\n<tbody>\n";
    for (const std::string& m : sceneMetricNames(s)) {
        std::vector<const Check*> checks;
        for (const Check& c : s.checks)
            if (c.metric == m) checks.push_back(&c);
        auto st = metricStatus(s, m);
        const bool na = isNotApplicable(s, m);
        // The row's id is what summary.md links to (report_markdown.h).
        h += fmt::format("<tr id=\"metric-{}\"><td class=\"mono\"{}>{}</td>", htmlEscape(m),
                         metricTitle(m), htmlEscape(m));
        h += valueCell(s, m, thresholdsFile);
        h += "<td class=\"unit\">" + htmlEscape(metricUnit(m)) + "</td>";
        h += "<td class=\"num\">" + htmlEscape(boundsText(checks, false)) + "</td>";
        h += "<td class=\"num\">" + htmlEscape(boundsText(checks, true)) + "</td>";
        if (hasBaseline)
            h += na ? "<td class=\"num\">—</td><td class=\"num\">—</td>"
                    : baselineCells(s, m, checks);
        h += "<td>" +
             (st ? badge(*st)
                 : fmt::format("<span class=\"muted small\">{}</span>",
                               na ? "not applicable" : "not checked")) +
             "</td></tr>\n";
    }
    // The metrics the test image's channels cannot give: listed, never a value, never checked.
    for (const std::string& m : s.notProvided)
        h += fmt::format(
            "<tr id=\"metric-{0}\"><td class=\"mono\"{1}>{0}</td><td class=\"num muted\">not "
            "provided</td><td class=\"unit\">{2}</td><td class=\"num\">—</td><td "
            "class=\"num\">—</td>{3}<td><span class=\"muted small\">not checked</span></td></tr>\n",
            htmlEscape(m), metricTitle(m), htmlEscape(metricUnit(m)),
            hasBaseline ? "<td class=\"num\">—</td><td class=\"num\">—</td>" : "");
    h += "</tbody></table></div>\n";
    std::vector<const Check*> notable;
    for (Status want : {Status::Fail, Status::Warn})
        for (const Check& c : s.checks)
            if (c.status == want) notable.push_back(&c);
    if (!notable.empty()) {
        h += "<ul class=\"messages\">\n";
        for (const Check* c : notable)
            h += fmt::format("<li class=\"{}\">{}</li>\n", toString(c->status),
                             htmlEscape(c->message));
        h += "</ul>\n";
    }
    return h;
}

// A stage's time, with a bar of its share of the renderer's total.
std::string stageCell(const std::map<std::string, double>& t, const std::string& stage) {
    auto it = t.find(stage);
    if (it == t.end()) return std::string("<td class=\"num muted\">—</td>");
    std::string bar;
    auto total = t.find("total");
    if (stage != "total" && total != t.end() && total->second > 0.0 && std::isfinite(it->second)) {
        const double share = std::clamp(it->second / total->second, 0.0, 1.0);
        bar = fmt::format(
            "<span class=\"bar\" style=\"width:{:.1f}px\" title=\"{:.0f} % of the "
            "total\"></span>",
            48.0 * share, 100.0 * share);
    }
    return fmt::format("<td class=\"num\">{:.2f}{}</td>", it->second, bar);
}

// A stage that did not run: 0 ms, or absent, in every renderer.
bool stageRan(const SceneReport& s, const std::vector<std::string>& renderers,
              const std::string& stage) {
    for (const auto& r : renderers) {
        const auto& t = s.renderers.at(r).timingsMs;
        if (auto it = t.find(stage); it != t.end() && it->second != 0.0) return true;
    }
    return false;
}

std::string timingTable(const SceneReport& s) {
    std::vector<std::string> renderers;
    for (const std::string& r : renderersOf(s))
        if (s.renderers.count(r)) renderers.push_back(r);
    for (const auto& [r, rr] : s.renderers)
        if (std::find(renderers.begin(), renderers.end(), r) == renderers.end())
            renderers.push_back(r);
    if (renderers.empty()) return "<p class=\"muted\">No timings.</p>\n";
    std::vector<std::string> stages, idle;
    for (const auto& r : renderers)
        for (const auto& [stage, ms] : s.renderers.at(r).timingsMs)
            if (stage != "total" && std::find(stages.begin(), stages.end(), stage) == stages.end())
                stages.push_back(stage);
    stages = core::inStageOrder(std::move(stages));  // the order a frame runs them
    std::string h = "<table class=\"timings\">\n<thead><tr><th>Stage</th>";
    for (const auto& r : renderers)
        h += "<th class=\"num\">" + htmlEscape(rendererLabel(s, r)) +
             " <span class=\"unit\">ms</span></th>";
    h += "</tr></thead>\n<tbody>\n";
    for (const auto& stage : stages) {
        if (!stageRan(s, renderers, stage)) {
            idle.push_back(stage);
            continue;
        }
        h += "<tr><td>" + htmlEscape(stage) + "</td>";
        for (const auto& r : renderers) h += stageCell(s.renderers.at(r).timingsMs, stage);
        h += "</tr>\n";
    }
    // The scene's time, the one every page shows (a sequence's median).
    const std::string basis = timeBasis(s);
    h +=
        "<tr class=\"total\"><td>total" + (basis.empty() ? "" : ", " + htmlEscape(basis)) + "</td>";
    for (const auto& r : renderers) {
        const auto t = sceneTimeMs(s, r);
        h += t ? fmt::format("<td class=\"num\">{:.2f}</td>", *t)
               : std::string("<td class=\"num muted\">—</td>");
    }
    h += "</tr>\n</tbody></table>\n";
    std::string notes;
    if (s.sequence && !basis.empty())
        notes +=
            fmt::format("The stages are frame {}'s (the frame shown). ", s.sequence->shownFrame);
    if (!idle.empty()) {
        std::string names;
        for (const auto& st : idle) names += (names.empty() ? "" : ", ") + st;
        notes += "Not run for this scene, so left out: " + htmlEscape(names) + ". ";
    }
    if (const std::string ratio = speedRatio(s); !ratio.empty())
        notes += "Speed-up, the reference's time over " +
                 htmlEscape(rendererLabel(s, testRenderer(s))) + "'s: " + htmlEscape(ratio) + ". ";
    h += "<p class=\"small muted\">" + notes +
         "Stage times: GL timer queries (real-time), wall clock (reference).</p>\n";
    return h;
}

std::string settingsTable(const SceneReport& s) {
    std::vector<std::pair<std::string, std::string>> rows;
    if (!s.settings.is_null())
        for (const auto& [key, value] : flattenSettings(s.settings))
            rows.emplace_back(key.empty() ? std::string("(value)") : key,
                              value.is_string() ? value.get<std::string>() : value.dump());
    if (rows.empty()) return "<p class=\"muted\">No settings recorded.</p>\n";
    std::string h = fmt::format(
        "<details open><summary>{} settings, by the dotted keys of the "
        "scene file and <code>--set</code></summary>\n"
        "<table class=\"settings\"><tbody>\n",
        rows.size());
    for (const auto& [k, v] : rows)
        h += "<tr><td>" + htmlEscape(k) + "</td><td>" + htmlEscape(v) + "</td></tr>\n";
    h += "</tbody></table></details>\n";
    return h;
}

std::string devicesTable(const SceneReport& s) {
    std::string h =
        "<table class=\"devices\">\n<thead><tr><th>Renderer</th><th>Device</th>"
        "<th>Counters</th></tr></thead>\n<tbody>\n";
    for (const auto& [r, rr] : s.renderers) {
        std::string counters;
        for (const auto& [k, v] : rr.counters)
            counters += (counters.empty() ? "" : ", ") + k + " = " + formatValue(v);
        h += "<tr><td>" + htmlEscape(rendererLabel(s, r)) + "</td><td>" +
             htmlEscape(rr.device.empty() ? "—" : rr.device) + "</td><td class=\"small\">" +
             htmlEscape(counters.empty() ? "—" : counters) + "</td></tr>\n";
    }
    h += "</tbody></table>\n";
    return h;
}

// ---- scene page: images ------------------------------------------------------------------

// A panel's placeholder where there is no image: for `buffer` (none when empty), `hidden`
// being "" or " hidden".
std::string panelNote(const std::string& buffer, const std::string& hidden,
                      const std::string& text) {
    return "<div" + (buffer.empty() ? "" : " data-buffer=\"" + htmlEscape(buffer) + "\"") +
           " class=\"note\" style=\"line-height:1.5;padding:2rem;color:#afb8c1\"" + hidden + ">" +
           text + "</div>";
}

// Buffers any renderer wrote, in the switch's order.
std::vector<std::string> sceneBuffers(const SceneReport& s) {
    std::vector<std::string> buffers;
    auto add = [&](const std::string& b) {
        if (std::find(buffers.begin(), buffers.end(), b) == buffers.end()) buffers.push_back(b);
    };
    for (const auto& b : bufferNames())
        for (const auto& [r, rr] : s.renderers)
            if (rr.images.count(b)) add(b);
    for (const auto& [r, rr] : s.renderers)
        for (const auto& [b, path] : rr.images) add(b);
    return buffers;
}

// The scene's neighbours in the run, for the links beside "All scenes".
struct Neighbours {
    const SceneReport* previous = nullptr;
    const SceneReport* next = nullptr;
};

std::string sceneNav(const Neighbours& n) {
    std::string h =
        "<nav class=\"scene-nav\"><a class=\"back\" href=\"../index.html\">← All "
        "scenes</a>";
    if (n.previous)
        h += fmt::format("<a rel=\"prev\" href=\"../{}/index.html\">‹ {}</a>",
                         urlPath(n.previous->name), htmlEscape(n.previous->name));
    if (n.next)
        h += fmt::format("<a rel=\"next\" href=\"../{}/index.html\">{} ›</a>",
                         urlPath(n.next->name), htmlEscape(n.next->name));
    return h + "</nav>";
}

std::string sceneHeader(const SceneReport& s, const Neighbours& n) {
    std::vector<std::string> facts;
    const std::string basis = timeBasis(s);
    for (const std::string& r : renderersOf(s)) {
        const auto t = sceneTimeMs(s, r);
        if (!t) continue;
        std::string fact = htmlEscape(rendererLabel(s, r)) + " " + htmlEscape(formatMs(*t));
        if (!basis.empty()) fact += " (" + htmlEscape(basis) + ")";
        if (const std::string d = deviceOf(s, r); !d.empty())
            fact += " on <b class=\"device\">" + htmlEscape(d) + "</b>";
        facts.push_back(fact);
    }
    if (const std::string ratio = speedRatio(s); !ratio.empty())
        facts.push_back("speed-up " + htmlEscape(ratio));
    if (!s.checks.empty()) {
        std::vector<Status> st;
        for (const Check& c : s.checks) st.push_back(c.status);
        facts.push_back(htmlEscape(countsText(st, "check")));
    }
    return pageHeader(s.name, s.status(), facts, sceneNav(n));
}

// The buttons that switch the shown buffer (keys 1, 2, ...).
std::string bufferSwitch(const std::vector<std::string>& buffers) {
    std::string h =
        "<div class=\"toolbar\">\n<div class=\"seg\" role=\"group\" aria-label=\"Buffer\">";
    for (std::size_t i = 0; i < buffers.size(); ++i)
        h += fmt::format(
            "<button type=\"button\" data-buffer=\"{0}\" aria-pressed=\"{1}\" "
            "title=\"key {2}\">{0}</button>",
            htmlEscape(buffers[i]), i == 0 ? "true" : "false", i + 1);
    return h + "</div>\n<span class=\"note\" id=\"buffer-note\"></span>\n</div>\n";
}

// One renderer's figure: an image per buffer, only the initial one shown.
std::string rendererPanel(const SceneReport& s, const std::string& r,
                          const std::vector<std::string>& buffers, const std::string& initial) {
    auto it = s.renderers.find(r);
    std::string h = fmt::format("<figure data-panel=\"{}\"><div class=\"frame\">", r);
    for (const auto& b : buffers) {
        const std::string hidden = b == initial ? "" : " hidden";
        if (it != s.renderers.end() && it->second.images.count(b))
            h += fmt::format("<img data-buffer=\"{}\" src=\"{}\" alt=\"{} {}\"{}>", htmlEscape(b),
                             urlPath(it->second.images.at(b)), htmlEscape(rendererLabel(s, r)),
                             htmlEscape(b), hidden);
        else
            h += panelNote(
                b, hidden,
                htmlEscape(rendererLabel(s, r)) + " wrote no " + htmlEscape(b) + " buffer");
    }
    auto t = sceneTimeMs(s, r);
    return h + fmt::format("</div><figcaption><b>{}</b><span>{}</span></figcaption></figure>\n",
                           htmlEscape(rendererLabel(s, r)), t ? htmlEscape(formatMs(*t)) : "");
}

// A map keyed BUFFER.NAME is a second map of BUFFER (error_maps.h), shown beside its first.
bool isSecondMap(const std::string& key) {
    return key.find('.') != std::string::npos;
}

// The maps whose values are codes, not amounts: {value, meaning} per code, drawn as swatches of
// the colour the map gives the value (compare/shadow_error.h's codes: 1 false, 2 missed).
const std::vector<std::pair<double, std::string>>* mapCategories(const std::string& key) {
    static const std::map<std::string, std::vector<std::pair<double, std::string>>> categories = {
        {"shadow", {{0.0, "agree (or no surface)"}, {1.0, "false shadow"}, {2.0, "missed shadow"}}},
    };
    const auto it = categories.find(key);
    return it == categories.end() ? nullptr : &it->second;
}

// What a map's caption says beside its label: the exposures of HDR-ꟻLIP (the scene's
// compare.hdrflip settings), else the colour map.
std::string mapNote(const SceneReport& s, const std::string& key) {
    if (key == "beauty.hdrflip" && s.settings.is_object() && s.settings.contains("compare")) {
        const json& c = s.settings["compare"];
        if (c.is_object() && c.contains("hdrflip")) {
            const json& e = c["hdrflip"];
            return fmt::format("{} exposures, {} to {} stops", e.value("exposures", 0),
                               formatValue(e.value("start_exposure", 0.0)),
                               formatValue(e.value("stop_exposure", 0.0)));
        }
    }
    return mapCategories(key) ? "one colour per case" : "magma colour map";
}

// The legend under a map: a colour bar over its range, or a swatch per code.
std::string mapLegend(const ErrorMapImage& m, const std::string& key) {
    if (const auto* codes = mapCategories(key)) {
        std::string h = "<div class=\"categories\">";
        for (const auto& [value, meaning] : *codes) {
            float rgb[3];
            compare::magma(m.hi > m.lo ? (value - m.lo) / (m.hi - m.lo) : 0.0, rgb);
            h += fmt::format(
                "<span><span class=\"swatch\" style=\"background:rgb({},{},{})\"></span>{}"
                "</span>",
                std::lround(255.0f * rgb[0]), std::lround(255.0f * rgb[1]),
                std::lround(255.0f * rgb[2]), htmlEscape(meaning));
        }
        return h + "</div>";
    }
    const std::string unit = m.unit.empty() ? "" : " " + m.unit;
    return fmt::format(
        "<div class=\"colourbar\" style=\"background:{}\"></div>"
        "<div class=\"colourbar-labels\"><span>{}{}</span><span>{}{}</span></div>",
        magmaCssGradient(), htmlEscape(formatValue(m.lo)), htmlEscape(unit),
        htmlEscape(formatValue(m.hi)), htmlEscape(unit));
}

// One error map with its caption and legend.
std::string errorMapFigure(const ErrorMapImage& m, const std::string& key,
                           const std::string& note) {
    return fmt::format(
        "<div class=\"frame\"><img src=\"{}\" alt=\"{}\"></div>"
        "<figcaption><b>{}</b><span>{}</span></figcaption>{}",
        urlPath(m.path), htmlEscape(m.label), htmlEscape(m.label), htmlEscape(note),
        mapLegend(m, key));
}

// The error panel: the map of the current buffer (and its second maps, as HDR-ꟻLIP's beside
// ꟻLIP's), else the beauty (ꟻLIP) map, with their colour bars. Sets the fallback in the page's
// data.
std::string errorPanel(const SceneReport& s, const std::string& initial, json& data) {
    std::string fallback;
    if (s.errorMaps.count("beauty"))
        fallback = "beauty";
    else
        for (const auto& [b, m] : s.errorMaps)
            if (!isSecondMap(b) && fallback.empty()) fallback = b;
    data["errorFallback"] = fallback;
    data["errorLabel"] = fallback.empty() ? "" : s.errorMaps.at(fallback).label;
    const std::string shownMap = s.errorMaps.count(initial) ? initial : fallback;
    std::string h = "<figure data-panel=\"error\">";
    if (fallback.empty())
        h += "<div class=\"frame\">" + panelNote("", "", "No error map was written.") + "</div>";
    for (const auto& [b, m] : s.errorMaps) {
        if (isSecondMap(b)) continue;
        h += fmt::format("<div data-buffer=\"{}\"{}>", htmlEscape(b),
                         b == shownMap ? "" : " hidden");
        h += errorMapFigure(m, b, mapNote(s, b));
        for (const auto& [k, second] : s.errorMaps)
            if (k.starts_with(b + "."))
                h += "<div class=\"second-map\">" + errorMapFigure(second, k, mapNote(s, k)) +
                     "</div>";
        h += "</div>";
    }
    return h + "</figure>\n";
}

// Swap view: the reference below, the real-time render above, clipped at the split. Puts
// every buffer's pair of images into the page's data.
std::string swapView(const SceneReport& s, const std::vector<std::string>& buffers,
                     const std::string& initial, json& data) {
    // The page's script names the measured renderer's slot "realtime", whichever it is.
    auto rt = s.renderers.find(testRenderer(s));
    auto ref = s.renderers.find("raymarch");
    for (const auto& b : buffers) {
        json pair = json::object();
        if (rt != s.renderers.end() && rt->second.images.count(b))
            pair["realtime"] = urlPath(rt->second.images.at(b));
        if (ref != s.renderers.end() && ref->second.images.count(b))
            pair["raymarch"] = urlPath(ref->second.images.at(b));
        data["buffers"][b] = pair;
    }
    if (rt == s.renderers.end() || ref == s.renderers.end()) return "";
    const json& first = data["buffers"][initial];
    const bool both = first.contains("realtime") && first.contains("raymarch");
    const std::string label = htmlEscape(rendererLabel(s, testRenderer(s)));
    std::string h = "<h2 style=\"margin-top:1.4rem\">Swap</h2>\n";
    h += fmt::format(
        "<div class=\"swap\" id=\"swap\"{0}><img id=\"swap-under\" src=\"{1}\" "
        "alt=\"Reference\">"
        "<div class=\"over\"><img id=\"swap-over\" src=\"{2}\" alt=\"{3}\"></div>"
        "<div class=\"split\"></div><span class=\"tag left\">{3}</span>"
        "<span class=\"tag right\">Reference</span></div>\n",
        both ? "" : " hidden", both ? first["raymarch"].get<std::string>() : "",
        both ? first["realtime"].get<std::string>() : "", label);
    h += fmt::format(
        "<div class=\"swap-controls\"><span>{0}</span><input type=\"range\" "
        "id=\"swap-range\" min=\"0\" max=\"100\" value=\"50\" aria-label=\"Split between "
        "the {0} and the reference render\"><span>Reference</span>"
        "<label><input type=\"checkbox\" id=\"swap-follow\" checked> follow the "
        "mouse</label><span id=\"swap-note\"></span></div>\n",
        label);
    return h;
}

std::string imagesSection(const SceneReport& s, const std::vector<std::string>& buffers,
                          json& data) {
    const std::string& initial = buffers.front();
    std::string h = "<section>\n<h2>Images</h2>\n" + bufferSwitch(buffers);
    h += "<div class=\"panels\">\n";
    for (const std::string& r : renderersOf(s)) h += rendererPanel(s, r, buffers, initial);
    h += errorPanel(s, initial, data) + "</div>\n";
    h += swapView(s, buffers, initial, data);
    h += "<p class=\"note\">Buffers: beauty tonemapped as displayed; normal as 0.5 + 0.5 n; "
         "uv as (u, v, 0); depth log-scaled, near white to far grey, the same range for both "
         "renders; id one colour per body; shadow white where lit; ao white where the "
         "hemisphere is open; emission tonemapped. "
         "Slate: no surface. Keys 1–" +
         std::to_string(buffers.size()) + " switch buffers.</p>\n</section>\n";
    return h;
}

// Links to the files the page is made from: the renders' AOV images and JSON, metrics.json.
std::string filesLine(const std::vector<std::pair<std::string, std::string>>& files) {
    if (files.empty()) return "";
    std::string h = "<p class=\"files small\">Files: ";
    for (std::size_t i = 0; i < files.size(); ++i)
        h += fmt::format("{}<a href=\"{}\">{}</a>", i ? ", " : "", urlPath(files[i].second),
                         htmlEscape(files[i].first));
    return h + ".</p>\n";
}

std::string scenePage(const RunReport& run, const SceneReport& s, const Neighbours& n) {
    const std::vector<std::string> buffers = sceneBuffers(s);
    std::string h = pageHead(s.name + " — " + run.title) + sceneHeader(s, n);
    if (!s.description.empty()) h += "<p class=\"lead\">" + htmlEscape(s.description) + "</p>\n";
    if (ranOnSoftwareRasteriser(s)) h += softwareRasteriserNote(deviceOf(s, "realtime"));
    h += filesLine(rawFiles(s));
    if (!s.error.empty())
        h += "<section><div class=\"error-box\">" + htmlEscape(s.error) + "</div></section>\n";
    // What scene.js needs: every buffer's pair of images and the error map to fall back to.
    json data = {{"initial", buffers.empty() ? "" : buffers.front()},
                 {"buffers", json::object()},
                 {"errorFallback", ""},
                 {"errorLabel", ""}};
    h += sequenceSection(s);
    h += testRenderersSection(s);
    if (!buffers.empty()) h += imagesSection(s, buffers, data);
    if (hasErrorSplit(s.metrics))
        h += "<section id=\"error-split\">\n<h2>Where the error comes from</h2>\n" +
             errorSplitBars(s.metrics, false) + "</section>\n";
    h += "<section>\n<h2>Metrics</h2>\n" + metricTable(s, run.thresholdsFile) + "</section>\n";
    h += "<section class=\"grid2\">\n<div>\n<h2>Timings</h2>\n" + timingTable(s) + "</div>\n";
    h += "<div>\n<h2>Devices</h2>\n" + devicesTable(s) + "</div>\n</section>\n";
    h += "<section>\n<h2>Settings</h2>\n" + settingsTable(s) + "</section>\n</main>\n";
    return h + pageFooter(run.createdAt, run.commandLine, "scene.js", data.dump());
}

}  // namespace

void writeHtmlReport(const RunReport& run, const fs::path& dir) {
    core::makeFolders(dir);
    for (std::size_t i = 0; i < run.scenes.size(); ++i) {
        const SceneReport& s = run.scenes[i];
        const Neighbours n{.previous = i > 0 ? &run.scenes[i - 1] : nullptr,
                           .next = i + 1 < run.scenes.size() ? &run.scenes[i + 1] : nullptr};
        core::makeFolders(dir / s.name);
        core::writeTextFile(dir / s.name / "index.html", scenePage(run, s, n));
    }
    core::writeTextFile(dir / "index.html", indexPage(run));
}

}  // namespace twinrender::report
