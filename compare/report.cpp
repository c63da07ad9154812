#include "compare/report.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/vec3.hpp>
#include <stdexcept>

#include "compare/baseline.h"
#include "compare/report_assets.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/shading.h"

namespace twinrender::compare {

namespace fs = std::filesystem;
using nlohmann::json;

// ---- statuses --------------------------------------------------------------------------

Status SceneReport::status() const {
    if (!error.empty()) return Status::Fail;
    return overallStatus(checks);
}

Status RunReport::status() const {
    Status s = Status::Pass;
    for (const SceneReport& scene : scenes) s = worst(s, scene.status());
    return s;
}

// ---- JSON ------------------------------------------------------------------------------

json jsonNumber(double value) {
    if (std::isnan(value)) return "NaN";
    if (std::isinf(value)) return value > 0 ? "Infinity" : "-Infinity";
    return value;
}

std::optional<double> numberFromJson(const json& value) {
    if (value.is_number()) return value.get<double>();
    if (value.is_string()) {
        const auto& s = value.get_ref<const std::string&>();
        if (s == "Infinity") return std::numeric_limits<double>::infinity();
        if (s == "-Infinity") return -std::numeric_limits<double>::infinity();
        if (s == "NaN") return std::numeric_limits<double>::quiet_NaN();
    }
    return std::nullopt;
}

namespace {

json metricsObject(const MetricValues& metrics) {
    json m = json::object();
    for (const auto& [k, v] : metrics) m[k] = jsonNumber(v);
    return m;
}

json checksArray(const std::vector<Check>& checks) {
    json a = json::array();
    for (const Check& c : checks) {
        json j = {
            {"metric", c.metric},           {"value", jsonNumber(c.value)}, {"bound", c.bound},
            {"limit", jsonNumber(c.limit)}, {"status", toString(c.status)}, {"message", c.message}};
        if (!c.where.empty()) j["where"] = c.where;
        if (c.baseline) {
            j["baseline"] = jsonNumber(*c.baseline);
            j["delta"] = jsonNumber(c.value - *c.baseline);
        }
        a.push_back(std::move(j));
    }
    return a;
}

json timingsObject(const SceneReport& scene) {
    json t = json::object();
    for (const auto& [renderer, r] : scene.renderers) {
        json stages = json::object();
        for (const auto& [stage, ms] : r.timingsMs) stages[stage] = jsonNumber(ms);
        t[renderer] = stages;
    }
    return t;
}

}  // namespace

json metricsJson(const SceneReport& scene) {
    json j = {{"scene", scene.name},
              {"description", scene.description},
              {"status", toString(scene.status())},
              {"metrics", metricsObject(scene.metrics)},
              {"checks", checksArray(scene.checks)},
              {"timings_ms", timingsObject(scene)}};
    if (!scene.error.empty()) j["error"] = scene.error;
    return j;
}

json summaryJson(const RunReport& run) {
    json scenes = json::array();
    for (const SceneReport& s : run.scenes) {
        json j = {{"name", s.name},
                  {"status", toString(s.status())},
                  {"metrics", metricsObject(s.metrics)},
                  {"timings_ms", timingsObject(s)},
                  {"checks", checksArray(s.checks)},
                  {"settings", s.settings}};
        if (!s.error.empty()) j["error"] = s.error;
        scenes.push_back(std::move(j));
    }
    return {{"status", toString(run.status())},
            {"scenes", scenes},
            {"thresholds", run.thresholdsFile},
            {"baseline", run.baselineFile},
            {"created", run.createdAt}};
}

std::string xmlEscape(std::string_view s, bool attribute) {
    std::string out;
    out.reserve(s.size());
    for (char ch : s) {
        const unsigned char c = static_cast<unsigned char>(ch);
        switch (ch) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += attribute ? "&quot;" : "\"";
                break;
            case '\n':
                out += attribute ? "&#10;" : "\n";
                break;
            case '\t':
                out += attribute ? "&#9;" : "\t";
                break;
            case '\r':
                break;
            default:
                if (c < 0x20)
                    out += ' ';  // not allowed in XML 1.0
                else
                    out += ch;
        }
    }
    return out;
}

// ---- JUnit -----------------------------------------------------------------------------

namespace {

// Full precision, for machines: the shortest form that reads back to the same double.
std::string exactValue(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return fmt::format("{}", v);
}

}  // namespace

std::string junitXml(const RunReport& run) {
    struct Case {
        std::string classname, name, properties, failure, failureMessage, error, out;
    };
    std::vector<Case> cases;
    double seconds = 0.0;
    for (const SceneReport& scene : run.scenes) {
        for (const auto& [renderer, r] : scene.renderers)
            if (auto it = r.timingsMs.find("total");
                it != r.timingsMs.end() && std::isfinite(it->second))
                seconds += it->second / 1000.0;
        const std::string classname = "twinrender." + scene.name;
        if (!scene.error.empty()) {
            cases.push_back({classname, "render", "", "", "", scene.error, ""});
            continue;
        }
        // Checks grouped by metric, in the order they come.
        std::vector<std::string> order;
        std::map<std::string, std::vector<const Check*>> byMetric;
        for (const Check& c : scene.checks) {
            if (!byMetric.count(c.metric)) order.push_back(c.metric);
            byMetric[c.metric].push_back(&c);
        }
        if (order.empty()) {
            cases.push_back(
                {classname, "render", "", "", "", "", "rendered and compared; no checks"});
            continue;
        }
        for (const std::string& metric : order) {
            const auto& checks = byMetric[metric];
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
            cases.push_back(std::move(k));
        }
    }
    std::size_t failures = 0, errors = 0;
    for (const Case& c : cases) {
        failures += !c.failure.empty();
        errors += !c.error.empty();
    }
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
    for (const Case& c : cases) {
        xml += fmt::format("    <testcase classname=\"{}\" name=\"{}\" time=\"0\"",
                           xmlEscape(c.classname, true), xmlEscape(c.name, true));
        if (c.properties.empty() && c.failure.empty() && c.error.empty() && c.out.empty()) {
            xml += "/>\n";
            continue;
        }
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
        xml += "    </testcase>\n";
    }
    xml += "  </testsuite>\n</testsuites>\n";
    return xml;
}

void writeMetricsJson(const SceneReport& scene, const fs::path& file) {
    if (file.has_parent_path()) fs::create_directories(file.parent_path());
    core::writeTextFile(file, metricsJson(scene).dump(2) + "\n");
}

void writeSummaryJson(const RunReport& run, const fs::path& file) {
    if (file.has_parent_path()) fs::create_directories(file.parent_path());
    core::writeTextFile(file, summaryJson(run).dump(2) + "\n");
}

void writeJunit(const RunReport& run, const fs::path& file) {
    if (file.has_parent_path()) fs::create_directories(file.parent_path());
    core::writeTextFile(file, junitXml(run));
}

// ---- images ----------------------------------------------------------------------------

const std::vector<std::string>& bufferNames() {
    static const std::vector<std::string> names = {"beauty", "normal", "uv",      "depth",
                                                   "id",     "shadow", "emission"};
    return names;
}

namespace {

// matplotlib's magma (CC0, van der Walt and Smith), every 16th of its 256 entries and the last;
// linear interpolation between them stays within 0.5 % of the full table.
constexpr std::array<std::array<float, 3>, 17> MAGMA = {{
    {0.001462f, 0.000466f, 0.013866f},
    {0.039608f, 0.031090f, 0.133515f},
    {0.113094f, 0.065492f, 0.276784f},
    {0.211718f, 0.061992f, 0.418647f},
    {0.316654f, 0.071690f, 0.485380f},
    {0.414709f, 0.110431f, 0.504662f},
    {0.512831f, 0.148179f, 0.507648f},
    {0.613617f, 0.181811f, 0.498536f},
    {0.716387f, 0.214982f, 0.475290f},
    {0.816914f, 0.255895f, 0.436461f},
    {0.904281f, 0.319610f, 0.388137f},
    {0.960949f, 0.418323f, 0.359630f},
    {0.986700f, 0.535582f, 0.382210f},
    {0.996096f, 0.653659f, 0.446213f},
    {0.996898f, 0.769591f, 0.534892f},
    {0.992440f, 0.884330f, 0.640099f},
    {0.987053f, 0.991438f, 0.749504f},
}};

// Table index i sits at t = 16 i / 255, the last at t = 1.
double magmaKnot(std::size_t i) {
    return i + 1 < MAGMA.size() ? 16.0 * i / 255.0 : 1.0;
}

// Background of every buffer but beauty: a dark slate, darker than any depth or shadow grey.
constexpr float BACKGROUND[3] = {0.10f, 0.11f, 0.13f};

void hsvToRgb(double h, double s, double v, float rgb[3]) {
    const double hh = (h - std::floor(h)) * 6.0;
    const int i = static_cast<int>(hh) % 6;
    const double f = hh - std::floor(hh);
    const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    double r = v, g = t, b = p;
    switch (i) {
        case 0:
            r = v;
            g = t;
            b = p;
            break;
        case 1:
            r = q;
            g = v;
            b = p;
            break;
        case 2:
            r = p;
            g = v;
            b = t;
            break;
        case 3:
            r = p;
            g = q;
            b = v;
            break;
        case 4:
            r = t;
            g = p;
            b = v;
            break;
        default:
            r = v;
            g = p;
            b = q;
            break;
    }
    rgb[0] = static_cast<float>(r);
    rgb[1] = static_cast<float>(g);
    rgb[2] = static_cast<float>(b);
}

float clamp01(float v) {
    return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
}

std::vector<std::string> channelsOf(std::string_view buffer) {
    if (buffer == "beauty") return {"R", "G", "B"};
    if (buffer == "normal") return {"N.X", "N.Y", "N.Z"};
    if (buffer == "uv") return {"uv.U", "uv.V"};
    if (buffer == "depth") return {"Z"};
    if (buffer == "id") return {"id"};
    if (buffer == "shadow") return {"shadow"};
    if (buffer == "emission") return {"emission.R", "emission.G", "emission.B"};
    throw std::invalid_argument(
        fmt::format("unknown buffer '{}'; buffers are beauty, normal, "
                    "uv, depth, id, shadow, emission",
                    buffer));
}

}  // namespace

void magma(double t, float rgb[3]) {
    t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
    std::size_t i = 0;
    while (i + 2 < MAGMA.size() && t > magmaKnot(i + 1)) ++i;
    const double a = magmaKnot(i), b = magmaKnot(i + 1);
    const double f = std::clamp((t - a) / (b - a), 0.0, 1.0);
    for (int c = 0; c < 3; ++c)
        rgb[c] = static_cast<float>(MAGMA[i][c] + f * (MAGMA[i + 1][c] - MAGMA[i][c]));
}

core::Image colourMapped(const core::Image& map, int channel, double lo, double hi) {
    if (channel < 0 || channel >= map.channelCount())
        throw std::invalid_argument(fmt::format("colourMapped: no channel {}", channel));
    core::Image out(map.width(), map.height(), {"R", "G", "B"});
    const double span = hi > lo ? hi - lo : 1.0;
    for (std::size_t p = 0; p < map.pixelCount(); ++p) {
        const float v = map.at(p, channel);
        float rgb[3] = {0.0f, 0.0f, 0.0f};
        if (!std::isnan(v)) magma((v - lo) / span, rgb);
        for (int c = 0; c < 3; ++c) out.at(p, c) = rgb[c];
    }
    return out;
}

void writeErrorMapPng(const core::Image& map, int channel, double lo, double hi,
                      const fs::path& png) {
    if (png.has_parent_path()) fs::create_directories(png.parent_path());
    core::writeImage(colourMapped(map, channel, lo, hi), png);
}

std::map<std::string, ErrorMapImage> writeErrorMapImages(
    const std::map<std::string, core::Image>& errorMaps, const fs::path& dir,
    const std::string& stem) {
    struct Style {
        const char* buffer;
        const char* label;
        double hi;  // 0: the map's own maximum
        const char* unit;
    };
    // Fixed ranges: about where each error becomes plainly visible, so colours mean the same
    // in every scene and run.
    const std::map<std::string, Style> styles = {
        {"beauty.flip", {"beauty", "ꟻLIP error", 1.0, ""}},
        {"normal", {"normal", "normal angle error", 30.0, "°"}},
        {"depth", {"depth", "relative depth error", 0.1, ""}},
        {"uv", {"uv", "uv distance", 0.05, ""}},
        {"id", {"id", "other body visible", 1.0, ""}},
        {"shadow", {"shadow", "shadow error (1 false, 2 missed)", 2.0, ""}},
        {"emission", {"emission", "emission RMS error", 0.0, ""}},
    };
    std::map<std::string, ErrorMapImage> out;
    for (const auto& [key, map] : errorMaps) {
        if (map.channelCount() < 1 || map.pixelCount() == 0) continue;
        auto it = styles.find(key);
        Style st = it != styles.end() ? it->second : Style{nullptr, nullptr, 0.0, ""};
        const std::string buffer = st.buffer ? st.buffer : key;
        double hi = st.hi;
        if (!(hi > 0.0)) {
            hi = 0.0;
            for (std::size_t p = 0; p < map.pixelCount(); ++p)
                if (std::isfinite(map.at(p, 0)))
                    hi = std::max(hi, static_cast<double>(map.at(p, 0)));
            if (!(hi > 0.0)) hi = 1.0;
        }
        const std::string name = stem + "." + buffer + ".png";
        writeErrorMapPng(map, 0, 0.0, hi, dir / name);
        out[buffer] = ErrorMapImage{name, st.label ? st.label : key + " error", 0.0, hi, st.unit};
    }
    return out;
}

std::pair<double, double> depthRange(const core::Image& a, const core::Image& b) {
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const core::Image* image : {&a, &b}) {
        const int z = image->channelIndex("Z");
        if (z < 0) continue;
        const int cov = image->channelIndex("A");
        for (std::size_t p = 0; p < image->pixelCount(); ++p) {
            const float d = image->at(p, z);
            if (!(d > 0.0f) || !std::isfinite(d) || (cov >= 0 && !(image->at(p, cov) > 0.0f)))
                continue;
            lo = std::min(lo, static_cast<double>(d));
            hi = std::max(hi, static_cast<double>(d));
        }
    }
    if (!(hi > 0.0)) return {0.0, 0.0};
    return {lo, hi};
}

core::Image visualiseBuffer(const core::Image& aov, std::string_view buffer,
                            const BufferVisualSettings& settings) {
    const std::vector<std::string> names = channelsOf(buffer);
    std::vector<int> ch;
    for (const auto& n : names) ch.push_back(aov.requireChannel(n));
    const int cov = aov.channelIndex("A");
    const int zc = aov.channelIndex("Z");
    auto covered = [&](std::size_t p) {
        if (cov >= 0) return aov.at(p, cov) > 0.0f;
        if (zc >= 0) return std::isfinite(aov.at(p, zc));
        return true;
    };
    std::pair<double, double> range = settings.depthRange;
    if (buffer == "depth" && !(range.first > 0.0 && range.second >= range.first))
        range = depthRange(aov, aov);
    const double logSpan = range.second > range.first && range.first > 0.0
                               ? std::log(range.second / range.first)
                               : 0.0;

    core::Image out(aov.width(), aov.height(), {"R", "G", "B"});
    for (std::size_t p = 0; p < aov.pixelCount(); ++p) {
        float rgb[3] = {BACKGROUND[0], BACKGROUND[1], BACKGROUND[2]};
        if (buffer == "beauty") {
            const glm::vec3 c = core::tonemap(
                glm::vec3(aov.at(p, ch[0]), aov.at(p, ch[1]), aov.at(p, ch[2])), settings.exposure);
            rgb[0] = c.r, rgb[1] = c.g, rgb[2] = c.b;
        } else if (covered(p)) {
            if (buffer == "normal") {
                for (int c = 0; c < 3; ++c) rgb[c] = clamp01(0.5f + 0.5f * aov.at(p, ch[c]));
            } else if (buffer == "uv") {
                rgb[0] = clamp01(aov.at(p, ch[0]));
                rgb[1] = clamp01(aov.at(p, ch[1]));
                rgb[2] = 0.0f;
            } else if (buffer == "depth") {
                const double z = aov.at(p, ch[0]);
                if (std::isfinite(z) && z > 0.0) {
                    // Near is white, far a dark grey (0.25), log-scaled: equal depth ratios get
                    // equal steps, as a log depth buffer spends its precision.
                    const double t = logSpan > 0.0
                                         ? std::clamp(std::log(z / range.first) / logSpan, 0.0, 1.0)
                                         : 0.0;
                    rgb[0] = rgb[1] = rgb[2] = static_cast<float>(1.0 - 0.75 * t);
                }
            } else if (buffer == "id") {
                const float id = aov.at(p, ch[0]);
                if (id >= 0.0f && std::isfinite(id)) {
                    // Golden-ratio hue steps: neighbouring ids get distant hues; the colour
                    // depends on the id only, so both renders colour a body alike.
                    const double k = std::round(id);
                    hsvToRgb(0.08 + 0.6180339887498949 * k, 0.62, 0.95, rgb);
                }
            } else if (buffer == "shadow") {
                rgb[0] = rgb[1] = rgb[2] = 0.3f + 0.7f * clamp01(aov.at(p, ch[0]));
            } else if (buffer == "emission") {
                const glm::vec3 c =
                    core::tonemap(glm::vec3(aov.at(p, ch[0]), aov.at(p, ch[1]), aov.at(p, ch[2])),
                                  settings.exposure);
                rgb[0] = c.r, rgb[1] = c.g, rgb[2] = c.b;
            }
        }
        for (int c = 0; c < 3; ++c) out.at(p, c) = rgb[c];
    }
    return out;
}

std::map<std::string, std::string> writeBufferImages(const core::Image& aov,
                                                     const core::Image* beautyDisplay,
                                                     const fs::path& dir, const std::string& stem,
                                                     const BufferVisualSettings& settings) {
    fs::create_directories(dir);
    std::map<std::string, std::string> written;
    for (const std::string& buffer : bufferNames()) {
        const std::string name = stem + "." + buffer + ".png";
        if (buffer == "beauty" && beautyDisplay) {
            const std::vector<std::string> rgb = {"R", "G", "B"};
            core::writeImage(beautyDisplay->select(rgb), dir / name);
            written[buffer] = name;
            continue;
        }
        bool has = true;
        for (const auto& c : channelsOf(buffer)) has = has && aov.hasChannel(c);
        if (!has) continue;
        core::writeImage(visualiseBuffer(aov, buffer, settings), dir / name);
        written[buffer] = name;
    }
    return written;
}

std::string metricUnit(std::string_view metric) {
    auto ends = [&](std::string_view s) {
        return metric.size() >= s.size() && metric.substr(metric.size() - s.size()) == s;
    };
    if (ends("psnr")) return "dB";
    if (ends("_deg")) return "°";
    if (ends("_px")) return "px";
    if (ends("_ms")) return "ms";
    return "";
}

// ---- HTML ------------------------------------------------------------------------------

namespace {

std::string esc(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    for (char c : s) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&#39;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

// A relative path as a URL: every byte outside the unreserved set and '/' percent-encoded.
std::string url(std::string_view path) {
    std::string out;
    for (char ch : path) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || c == '/')
            out += ch;
        else
            out += fmt::format("%{:02X}", c);
    }
    return out;
}

std::string asset(std::string_view name) {
    auto text = findReportAsset(name);
    if (!text) throw std::logic_error(fmt::format("report asset '{}' is not embedded", name));
    return std::string(*text);
}

// Inline <script> text must not contain "</" (it would end the element early).
std::string scriptSafe(std::string text) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/')
            out += "<\\";
        else
            out += text[i];
    }
    return out;
}

std::string rendererLabel(const std::string& renderer) {
    if (renderer == "realtime") return "Real-time";
    if (renderer == "raymarch") return "Reference";
    return renderer;
}

std::string statusClass(Status s) {
    return std::string(toString(s));
}

std::string badge(Status s) {
    return fmt::format("<span class=\"badge {0}\">{0}</span>", toString(s));
}

std::string formatMs(double ms) {
    if (!std::isfinite(ms)) return formatValue(ms);
    if (ms < 1.0) return fmt::format("{:.2f} ms", ms);
    if (ms < 1000.0) return fmt::format("{:.1f} ms", ms);
    if (ms < 60000.0) return fmt::format("{:.2f} s", ms / 1000.0);
    return fmt::format("{:.0f} min {:.0f} s", std::floor(ms / 60000.0),
                       std::fmod(ms, 60000.0) / 1000.0);
}

std::optional<double> totalMs(const SceneReport& s, const std::string& renderer) {
    auto r = s.renderers.find(renderer);
    if (r == s.renderers.end()) return std::nullopt;
    auto t = r->second.timingsMs.find("total");
    if (t == r->second.timingsMs.end()) return std::nullopt;
    return t->second;
}

std::string speedRatio(const SceneReport& s) {
    auto rt = totalMs(s, "realtime"), ref = totalMs(s, "raymarch");
    if (!rt || !ref || !(*rt > 0.0) || !std::isfinite(*ref)) return "";
    const double r = *ref / *rt;
    return r >= 100  ? fmt::format("{:.0f}×", r)
           : r >= 10 ? fmt::format("{:.1f}×", r)
                     : fmt::format("{:.2f}×", r);
}

const std::vector<std::string>& metricOrder() {
    static const std::vector<std::string> order = {
        "beauty.psnr",  "beauty.ssim",         "beauty.flip",
        "coverage.iou", "silhouette.mean_px",  "depth.rel_mean",
        "id.mismatch",  "normal.mean_deg",     "normal.p95_deg",
        "uv.mean",      "emission.rmse",       "smoothness.ratio",
        "shadow.iou",   "shadow.false_shadow", "shadow.missed_shadow"};
    return order;
}

bool metricLess(const std::string& a, const std::string& b) {
    const auto& o = metricOrder();
    const auto ia = std::find(o.begin(), o.end(), a) - o.begin();
    const auto ib = std::find(o.begin(), o.end(), b) - o.begin();
    return ia != ib ? ia < ib : a < b;
}

// Metrics of a scene with their values, and the checked ones that are missing, in order.
std::vector<std::string> sceneMetricNames(const SceneReport& s) {
    std::vector<std::string> names;
    for (const auto& [k, v] : s.metrics) names.push_back(k);
    for (const Check& c : s.checks)
        if (!s.metrics.count(c.metric) &&
            std::find(names.begin(), names.end(), c.metric) == names.end())
            names.push_back(c.metric);
    std::sort(names.begin(), names.end(), metricLess);
    return names;
}

std::optional<Status> metricStatus(const SceneReport& s, const std::string& metric) {
    std::optional<Status> st;
    for (const Check& c : s.checks)
        if (c.metric == metric) st = st ? worst(*st, c.status) : c.status;
    return st;
}

std::string valueCell(const SceneReport& s, const std::string& metric) {
    auto st = metricStatus(s, metric);
    auto it = s.metrics.find(metric);
    const std::string text = it == s.metrics.end() ? "—" : formatValue(it->second);
    std::string title;
    for (const Check& c : s.checks)
        if (c.metric == metric) title += (title.empty() ? "" : "\n") + c.message;
    return fmt::format("<td class=\"num{}\"{}>{}</td>", st ? " " + statusClass(*st) : "",
                       title.empty() ? "" : " title=\"" + esc(title) + "\"", esc(text));
}

std::string pageStart(const std::string& title) {
    // The policy allows inline style and script and local images only: any reference to the
    // network is blocked (and reported by the self-test), so the report provably works offline.
    return fmt::format(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
        "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; "
        "img-src 'self' file: data:; style-src 'unsafe-inline'; script-src 'unsafe-inline'\">\n"
        "<title>{}</title>\n<link rel=\"icon\" href=\"data:,\">\n<script>\n{}</script>\n"
        "<style>\n{}</style>\n</head>\n<body>\n",
        esc(title), scriptSafe(asset("selftest.js")), asset("report.css"));
}

std::string pageEnd(const RunReport& run, const std::string& script, const std::string& data) {
    std::string f = "<footer>\n";
    f += "<div>Made by <b>twinrender</b>";
    if (!run.createdAt.empty()) f += " on " + esc(run.createdAt);
    f += ".";
    if (!run.commandLine.empty()) f += " Reproduce with <code>" + esc(run.commandLine) + "</code>.";
    f +=
        "</div>\n<pre id=\"selftest\" data-status=\"pending\">selftest: pending</pre>\n</footer>\n";
    if (!data.empty())
        f += "<script type=\"application/json\" id=\"buffers\">" + scriptSafe(data) + "</script>\n";
    f += "<script>\n" + scriptSafe(asset(script)) + "</script>\n</body>\n</html>\n";
    return f;
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

// ---- index.html --------------------------------------------------------------------------

std::string indexPage(const RunReport& run) {
    std::vector<Status> sceneStatuses;
    for (const auto& s : run.scenes) sceneStatuses.push_back(s.status());
    const Status verdict = run.status();

    // Key metrics: those of DESIGN.md's list that any scene has, in its order.
    std::vector<std::string> columns;
    for (const std::string& m :
         {std::string("beauty.psnr"), std::string("beauty.ssim"), std::string("beauty.flip"),
          std::string("coverage.iou"), std::string("silhouette.mean_px"),
          std::string("depth.rel_mean"), std::string("id.mismatch"), std::string("normal.mean_deg"),
          std::string("shadow.iou")}) {
        bool any = false;
        for (const auto& s : run.scenes) {
            any = any || s.metrics.count(m);
            for (const Check& c : s.checks) any = any || c.metric == m;
        }
        if (any) columns.push_back(m);
    }

    std::string h = pageStart(run.title);
    h += "<header class=\"top\">\n";
    h += fmt::format("<h1>{}</h1> {}\n", esc(run.title), badge(verdict));
    h += "<div class=\"facts\"><span>" + esc(countsText(sceneStatuses, "scene")) + "</span>";
    if (!run.createdAt.empty()) h += "<span>" + esc(run.createdAt) + "</span>";
    if (!run.thresholdsFile.empty())
        h += "<span>thresholds <code>" + esc(run.thresholdsFile) + "</code></span>";
    h += run.baselineFile.empty()
             ? std::string("<span>no baseline</span>")
             : "<span>baseline <code>" + esc(run.baselineFile) + "</code></span>";
    for (const auto& [text, href] : run.links)
        h += "<span><a href=\"" + url(href) + "\">" + esc(text) + "</a></span>";
    h += "</div>\n</header>\n<main>\n<section>\n";

    if (run.scenes.empty()) {
        h += "<p class=\"muted\">No scenes were run.</p>\n";
    } else {
        h += "<div class=\"scroll\"><table class=\"scenes\">\n<thead><tr><th></th><th>Scene</th>"
             "<th>Verdict</th>";
        for (const auto& m : columns) {
            const std::string unit = metricUnit(m);
            h += fmt::format("<th class=\"num\"><span class=\"mono\">{}</span>{}</th>", esc(m),
                             unit.empty() ? "" : " <span class=\"unit\">" + esc(unit) + "</span>");
        }
        h += "<th class=\"num\">Real-time <span class=\"unit\">ms</span></th>"
             "<th class=\"num\">Reference <span class=\"unit\">ms</span></th>"
             "<th class=\"num\" title=\"reference time over real-time time\">Speed-up</th>"
             "</tr></thead>\n<tbody>\n";
        for (const SceneReport& s : run.scenes) {
            const std::string page = url(s.name) + "/index.html";
            std::string thumb;
            for (const char* r : {"realtime", "raymarch"}) {
                auto it = s.renderers.find(r);
                if (it == s.renderers.end()) continue;
                auto img = it->second.images.find("beauty");
                if (img == it->second.images.end()) continue;
                thumb = fmt::format(
                    "<a href=\"{}\"><img class=\"thumb\" src=\"{}\" alt=\"{} {}\"></a>", page,
                    url(s.name + "/" + img->second), esc(s.name), esc(rendererLabel(r)));
                break;
            }
            std::vector<std::pair<Status, std::string>> problems;
            if (!s.error.empty()) problems.emplace_back(Status::Fail, s.error);
            for (Status want : {Status::Fail, Status::Warn})
                for (const Check& c : s.checks)
                    if (c.status == want) problems.emplace_back(want, c.message);
            h += fmt::format("<tr{}><td>{}</td>", problems.empty() ? "" : " class=\"has-problems\"",
                             thumb);
            h += fmt::format("<td class=\"scene\"><a href=\"{}\">{}</a>{}</td>", page, esc(s.name),
                             s.description.empty()
                                 ? ""
                                 : "<div class=\"desc\">" + esc(s.description) + "</div>");
            h += "<td>" + badge(s.status()) + "</td>";
            for (const auto& m : columns) h += valueCell(s, m);
            auto rt = totalMs(s, "realtime"), ref = totalMs(s, "raymarch");
            h += fmt::format(
                "<td class=\"num\">{}</td><td class=\"num\">{}</td><td "
                "class=\"num\">{}</td></tr>\n",
                rt ? fmt::format("{:.1f}", *rt) : "—", ref ? fmt::format("{:.1f}", *ref) : "—",
                esc(speedRatio(s)));
            // Problems under the row, across the metric columns: the failing checks first.
            if (!problems.empty()) {
                h += fmt::format(
                    "<tr class=\"problems\"><td colspan=\"2\"></td><td colspan=\"{}\"><ul>",
                    columns.size() + 4);
                const std::size_t shown = problems.size() > 4 ? 3 : problems.size();
                for (std::size_t i = 0; i < shown; ++i)
                    h += fmt::format("<li class=\"{}\">{}</li>", statusClass(problems[i].first),
                                     esc(problems[i].second));
                if (problems.size() > shown)
                    h += fmt::format("<li><a href=\"{}\">{} more on the scene page</a></li>", page,
                                     problems.size() - shown);
                h += "</ul></td></tr>\n";
            }
        }
        h += "</tbody></table></div>\n";
        h += "<div class=\"legend-row\"><span><span class=\"swatch pass\"></span>within its "
             "bounds</span><span><span class=\"swatch warn\"></span>beyond a warn bound</span>"
             "<span><span class=\"swatch fail\"></span>beyond a fail bound or the baseline</span>"
             "<span>uncoloured: no bound set. Times: total render, without start-up and file "
             "I/O.</span></div>\n";
    }
    h += "</section>\n</main>\n";
    h += pageEnd(run, "index.js", "");
    return h;
}

// ---- scene page --------------------------------------------------------------------------

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

std::string metricTable(const SceneReport& s) {
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
        auto it = s.metrics.find(m);
        const std::string unit = metricUnit(m);
        h += fmt::format("<tr><td class=\"mono\">{}</td>", esc(m));
        h += valueCell(s, m);
        h += "<td class=\"unit\">" + esc(unit) + "</td>";
        h += "<td class=\"num\">" + esc(boundsText(checks, false)) + "</td>";
        h += "<td class=\"num\">" + esc(boundsText(checks, true)) + "</td>";
        if (hasBaseline) {
            std::optional<double> base;
            if (auto b = s.baseline.find(m); b != s.baseline.end()) base = b->second;
            for (const Check* c : checks)
                if (c->baseline) base = *c->baseline;
            std::string delta;
            if (base && it != s.metrics.end()) {
                const double d = it->second - *base;
                const BaselinePolicy p = defaultPolicy(m);
                const double worsening =
                    p.better == Better::Higher ? -d
                    : p.better == Better::Lower
                        ? d
                        : std::abs(it->second - p.origin) - std::abs(*base - p.origin);
                const char* cls = worsening > 0   ? "delta-worse"
                                  : worsening < 0 ? "delta-better"
                                                  : "";
                std::string text = fmt::format("{}{}", d > 0 ? "+" : "", formatValue(d));
                if (*base != 0.0 && std::isfinite(d) && std::isfinite(*base) && d != 0.0)
                    text +=
                        fmt::format(" ({}{:.1f} %)", d > 0 ? "+" : "", 100.0 * d / std::abs(*base));
                delta = fmt::format("<span class=\"{}\">{}</span>", cls, esc(text));
            }
            h += "<td class=\"num\">" + (base ? esc(formatValue(*base)) : std::string("—")) +
                 "</td>";
            h += "<td class=\"num\">" + (delta.empty() ? std::string("—") : delta) + "</td>";
        }
        h += "<td>" +
             (st ? badge(*st) : std::string("<span class=\"muted small\">not checked</span>")) +
             "</td></tr>\n";
    }
    h += "</tbody></table></div>\n";
    std::vector<const Check*> notable;
    for (Status want : {Status::Fail, Status::Warn})
        for (const Check& c : s.checks)
            if (c.status == want) notable.push_back(&c);
    if (!notable.empty()) {
        h += "<ul class=\"messages\">\n";
        for (const Check* c : notable)
            h += fmt::format("<li class=\"{}\">{}</li>\n", statusClass(c->status), esc(c->message));
        h += "</ul>\n";
    }
    return h;
}

const std::vector<std::string>& stageOrder() {
    static const std::vector<std::string> order = {"shadow", "gbuffer", "ssss", "shade",
                                                   "post",   "build",   "trace"};
    return order;
}

std::string timingTable(const SceneReport& s) {
    std::vector<std::string> renderers;
    for (const char* r : {"realtime", "raymarch"})
        if (s.renderers.count(r)) renderers.push_back(r);
    for (const auto& [r, rr] : s.renderers)
        if (r != "realtime" && r != "raymarch") renderers.push_back(r);
    if (renderers.empty()) return "<p class=\"muted\">No timings.</p>\n";
    std::vector<std::string> stages;
    for (const auto& r : renderers)
        for (const auto& [stage, ms] : s.renderers.at(r).timingsMs)
            if (stage != "total" && std::find(stages.begin(), stages.end(), stage) == stages.end())
                stages.push_back(stage);
    std::stable_sort(stages.begin(), stages.end(), [](const std::string& a, const std::string& b) {
        const auto& o = stageOrder();
        const auto ia = std::find(o.begin(), o.end(), a) - o.begin();
        const auto ib = std::find(o.begin(), o.end(), b) - o.begin();
        return ia != ib ? ia < ib : a < b;
    });
    std::string h = "<table class=\"timings\">\n<thead><tr><th>Stage</th>";
    for (const auto& r : renderers)
        h += "<th class=\"num\">" + esc(rendererLabel(r)) + " <span class=\"unit\">ms</span></th>";
    h += "</tr></thead>\n<tbody>\n";
    auto cell = [&](const std::string& r, const std::string& stage) {
        const auto& t = s.renderers.at(r).timingsMs;
        auto it = t.find(stage);
        if (it == t.end()) return std::string("<td class=\"num muted\">—</td>");
        std::string bar;
        auto total = t.find("total");
        if (stage != "total" && total != t.end() && total->second > 0.0 &&
            std::isfinite(it->second)) {
            const double share = std::clamp(it->second / total->second, 0.0, 1.0);
            bar = fmt::format(
                "<span class=\"bar\" style=\"width:{:.1f}px\" title=\"{:.0f} % of the "
                "total\"></span>",
                48.0 * share, 100.0 * share);
        }
        return fmt::format("<td class=\"num\">{:.2f}{}</td>", it->second, bar);
    };
    for (const auto& stage : stages) {
        h += "<tr><td>" + esc(stage) + "</td>";
        for (const auto& r : renderers) h += cell(r, stage);
        h += "</tr>\n";
    }
    h += "<tr class=\"total\"><td>total</td>";
    for (const auto& r : renderers) h += cell(r, "total");
    h += "</tr>\n</tbody></table>\n";
    const std::string ratio = speedRatio(s);
    if (!ratio.empty())
        h += "<p class=\"small muted\">The reference takes " + esc(ratio) +
             " the real-time renderer's time. Stage times: GL timer queries (real-time), wall "
             "clock (reference).</p>\n";
    return h;
}

void flattenJson(const json& j, const std::string& prefix,
                 std::vector<std::pair<std::string, std::string>>& out) {
    if (j.is_object() && !j.empty()) {
        for (const auto& [k, v] : j.items())
            flattenJson(v, prefix.empty() ? k : prefix + "." + k, out);
        return;
    }
    out.emplace_back(prefix.empty() ? std::string("(value)") : prefix,
                     j.is_string() ? j.get<std::string>() : j.dump());
}

std::string settingsTable(const SceneReport& s) {
    std::vector<std::pair<std::string, std::string>> rows;
    if (!s.settings.is_null()) flattenJson(s.settings, "", rows);
    if (rows.empty()) return "<p class=\"muted\">No settings recorded.</p>\n";
    std::string h = fmt::format(
        "<details open><summary>{} settings, by the dotted keys of the "
        "scene file and <code>--set</code></summary>\n"
        "<table class=\"settings\"><tbody>\n",
        rows.size());
    for (const auto& [k, v] : rows)
        h += "<tr><td>" + esc(k) + "</td><td>" + esc(v) + "</td></tr>\n";
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
        h += "<tr><td>" + esc(rendererLabel(r)) + "</td><td>" +
             esc(rr.device.empty() ? "—" : rr.device) + "</td><td class=\"small\">" +
             esc(counters.empty() ? "—" : counters) + "</td></tr>\n";
    }
    h += "</tbody></table>\n";
    return h;
}

std::string colourBarCss() {
    std::string g = "linear-gradient(to right";
    for (int i = 0; i <= 16; ++i) {
        float rgb[3];
        magma(i / 16.0, rgb);
        g += fmt::format(", rgb({},{},{}) {:.2f}%", static_cast<int>(std::lround(255 * rgb[0])),
                         static_cast<int>(std::lround(255 * rgb[1])),
                         static_cast<int>(std::lround(255 * rgb[2])), 100.0 * i / 16.0);
    }
    return g + ")";
}

std::string scenePage(const RunReport& run, const SceneReport& s) {
    const Status verdict = s.status();
    // Buffers any renderer wrote, in the switch's order.
    std::vector<std::string> buffers;
    for (const auto& b : bufferNames())
        for (const auto& [r, rr] : s.renderers)
            if (rr.images.count(b) && std::find(buffers.begin(), buffers.end(), b) == buffers.end())
                buffers.push_back(b);
    for (const auto& [r, rr] : s.renderers)
        for (const auto& [b, path] : rr.images)
            if (std::find(buffers.begin(), buffers.end(), b) == buffers.end()) buffers.push_back(b);
    const std::string initial = buffers.empty() ? "" : buffers.front();

    std::string h = pageStart(s.name + " — " + run.title);
    h += "<header class=\"top\">\n<a class=\"back\" href=\"../index.html\">← All scenes</a>\n";
    h += fmt::format("<h1>{}</h1> {}\n<div class=\"facts\">", esc(s.name), badge(verdict));
    for (const char* r : {"realtime", "raymarch"})
        if (auto t = totalMs(s, r))
            h += "<span>" + esc(rendererLabel(r)) + " " + esc(formatMs(*t)) + "</span>";
    if (const std::string ratio = speedRatio(s); !ratio.empty())
        h += "<span>reference/real-time " + esc(ratio) + "</span>";
    if (!s.checks.empty()) {
        std::vector<Status> st;
        for (const Check& c : s.checks) st.push_back(c.status);
        h += "<span>" + esc(countsText(st, "check")) + "</span>";
    }
    h += "</div>\n</header>\n<main>\n";
    if (!s.description.empty()) h += "<p class=\"lead\">" + esc(s.description) + "</p>\n";
    if (!s.error.empty())
        h += "<section><div class=\"error-box\">" + esc(s.error) + "</div></section>\n";

    json data = {{"initial", initial},
                 {"buffers", json::object()},
                 {"errorFallback", ""},
                 {"errorLabel", ""}};
    if (!buffers.empty()) {
        h += "<section>\n<h2>Images</h2>\n<div class=\"toolbar\">\n"
             "<div class=\"seg\" role=\"group\" aria-label=\"Buffer\">";
        for (std::size_t i = 0; i < buffers.size(); ++i)
            h += fmt::format(
                "<button type=\"button\" data-buffer=\"{0}\" aria-pressed=\"{1}\" "
                "title=\"key {2}\">{0}</button>",
                esc(buffers[i]), i == 0 ? "true" : "false", i + 1);
        h += "</div>\n<span class=\"note\" id=\"buffer-note\"></span>\n</div>\n<div "
             "class=\"panels\">\n";
        for (const char* r : {"realtime", "raymarch"}) {
            auto it = s.renderers.find(r);
            h += fmt::format("<figure data-panel=\"{}\"><div class=\"frame\">", r);
            for (const auto& b : buffers) {
                const bool has = it != s.renderers.end() && it->second.images.count(b);
                if (has)
                    h += fmt::format("<img data-buffer=\"{}\" src=\"{}\" alt=\"{} {}\"{}>", esc(b),
                                     url(it->second.images.at(b)), esc(rendererLabel(r)), esc(b),
                                     b == initial ? "" : " hidden");
                else
                    h += fmt::format(
                        "<div data-buffer=\"{}\" class=\"note\" style=\"line-height:1.5;"
                        "padding:2rem;color:#afb8c1\"{}>{} wrote no {} buffer</div>",
                        esc(b), b == initial ? "" : " hidden", esc(rendererLabel(r)), esc(b));
            }
            auto t = totalMs(s, r);
            h += fmt::format("</div><figcaption><b>{}</b><span>{}</span></figcaption></figure>\n",
                             esc(rendererLabel(r)), t ? esc(formatMs(*t)) : "");
        }
        // Error panel: the map of the current buffer, else the beauty (ꟻLIP) map.
        std::string fallback;
        if (s.errorMaps.count("beauty"))
            fallback = "beauty";
        else if (!s.errorMaps.empty())
            fallback = s.errorMaps.begin()->first;
        data["errorFallback"] = fallback;
        data["errorLabel"] = fallback.empty() ? "" : s.errorMaps.at(fallback).label;
        const std::string shownMap = s.errorMaps.count(initial) ? initial : fallback;
        const std::string bar = colourBarCss();
        h += "<figure data-panel=\"error\">";
        if (s.errorMaps.empty()) {
            h += "<div class=\"frame\"><div class=\"note\" style=\"line-height:1.5;padding:2rem;"
                 "color:#afb8c1\">No error map was written.</div></div>";
        }
        for (const auto& [b, m] : s.errorMaps) {
            const std::string unit = m.unit.empty() ? "" : " " + m.unit;
            h += fmt::format(
                "<div data-buffer=\"{}\"{}><div class=\"frame\"><img src=\"{}\" alt=\"{}\"></div>"
                "<figcaption><b>{}</b><span>magma colour map</span></figcaption>"
                "<div class=\"colourbar\" style=\"background:{}\"></div>"
                "<div class=\"colourbar-labels\"><span>{}{}</span><span>{}{}</span></div></div>",
                esc(b), b == shownMap ? "" : " hidden", url(m.path), esc(m.label), esc(m.label),
                bar, esc(formatValue(m.lo)), esc(unit), esc(formatValue(m.hi)), esc(unit));
        }
        h += "</figure>\n</div>\n";

        // Swap view: the reference below, the real-time render above, clipped at the split.
        auto rt = s.renderers.find("realtime");
        auto ref = s.renderers.find("raymarch");
        for (const auto& b : buffers) {
            json pair = json::object();
            if (rt != s.renderers.end() && rt->second.images.count(b))
                pair["realtime"] = url(rt->second.images.at(b));
            if (ref != s.renderers.end() && ref->second.images.count(b))
                pair["raymarch"] = url(ref->second.images.at(b));
            data["buffers"][b] = pair;
        }
        const json& first = data["buffers"][initial];
        if (rt != s.renderers.end() && ref != s.renderers.end()) {
            const bool both = first.contains("realtime") && first.contains("raymarch");
            h += "<h2 style=\"margin-top:1.4rem\">Swap</h2>\n";
            h += fmt::format(
                "<div class=\"swap\" id=\"swap\"{}><img id=\"swap-under\" src=\"{}\" "
                "alt=\"Reference\">"
                "<div class=\"over\"><img id=\"swap-over\" src=\"{}\" alt=\"Real-time\"></div>"
                "<div class=\"split\"></div><span class=\"tag left\">Real-time</span>"
                "<span class=\"tag right\">Reference</span></div>\n",
                both ? "" : " hidden", both ? first["raymarch"].get<std::string>() : "",
                both ? first["realtime"].get<std::string>() : "");
            h += "<div class=\"swap-controls\"><span>Real-time</span><input type=\"range\" "
                 "id=\"swap-range\" min=\"0\" max=\"100\" value=\"50\" aria-label=\"Split between "
                 "the real-time and the reference render\"><span>Reference</span>"
                 "<label><input type=\"checkbox\" id=\"swap-follow\" checked> follow the "
                 "mouse</label><span id=\"swap-note\"></span></div>\n";
        }
        h += "<p class=\"note\">Buffers: beauty tonemapped as displayed; normal as 0.5 + 0.5 n; "
             "uv as (u, v, 0); depth log-scaled, near white to far grey, the same range for both "
             "renders; id one colour per body; shadow white where lit; emission tonemapped. "
             "Slate: no surface. Keys 1–" +
             std::to_string(buffers.size()) + " switch buffers.</p>\n</section>\n";
    }

    h += "<section>\n<h2>Metrics</h2>\n" + metricTable(s) + "</section>\n";
    h += "<section class=\"grid2\">\n<div>\n<h2>Timings</h2>\n" + timingTable(s) + "</div>\n";
    h += "<div>\n<h2>Devices</h2>\n" + devicesTable(s) + "</div>\n</section>\n";
    h += "<section>\n<h2>Settings</h2>\n" + settingsTable(s) + "</section>\n</main>\n";
    h += pageEnd(run, "scene.js", data.dump());
    return h;
}

}  // namespace

void writeHtmlReport(const RunReport& run, const fs::path& dir) {
    fs::create_directories(dir);
    for (const SceneReport& s : run.scenes) {
        fs::create_directories(dir / s.name);
        core::writeTextFile(dir / s.name / "index.html", scenePage(run, s));
    }
    core::writeTextFile(dir / "index.html", indexPage(run));
}

void writeReport(const RunReport& run, const fs::path& dir) {
    fs::create_directories(dir);
    for (const SceneReport& s : run.scenes) writeMetricsJson(s, dir / s.name / "metrics.json");
    writeSummaryJson(run, dir / "summary.json");
    writeHtmlReport(run, dir);
}

}  // namespace twinrender::compare

// ---- Shared with other reports and with `merge` -------------------------------------------

namespace twinrender::compare {

std::optional<Status> statusFromString(std::string_view text) {
    for (Status s : {Status::Pass, Status::Warn, Status::Fail})
        if (toString(s) == text) return s;
    return std::nullopt;
}

json sceneReportJson(const SceneReport& scene) {
    json j = metricsJson(scene);
    j["baseline"] = metricsObject(scene.baseline);
    json renderers = json::object();
    for (const auto& [name, r] : scene.renderers) {
        json t = json::object(), c = json::object();
        for (const auto& [k, v] : r.timingsMs) t[k] = jsonNumber(v);
        for (const auto& [k, v] : r.counters) c[k] = jsonNumber(v);
        renderers[name] = {{"timings_ms", t}, {"device", r.device}, {"counters", c}, {"images", r.images}};
    }
    j["renderers"] = renderers;
    json maps = json::object();
    for (const auto& [buffer, m] : scene.errorMaps)
        maps[buffer] = {{"path", m.path}, {"label", m.label}, {"lo", jsonNumber(m.lo)},
                        {"hi", jsonNumber(m.hi)}, {"unit", m.unit}};
    j["error_maps"] = maps;
    j["settings"] = scene.settings;
    return j;
}

SceneReport sceneReportFromJson(const json& j, const std::string& source) {
    auto bad = [&](const std::string& what) {
        return core::InputError(fmt::format("{}: {} (expected a scene report as twinrender writes it)", source, what));
    };
    auto number = [&](const json& v, const std::string& where) {
        const auto n = numberFromJson(v);
        if (!n) throw bad(where + " is not a number");
        return *n;
    };
    auto numbers = [&](const json& obj, const std::string& where) {
        std::map<std::string, double> m;
        if (obj.is_null()) return m;
        if (!obj.is_object()) throw bad(where + " is not an object");
        for (const auto& [k, v] : obj.items()) m[k] = number(v, where + "." + k);
        return m;
    };
    try {
        SceneReport s;
        s.name = j.at("scene").get<std::string>();
        s.description = j.value("description", "");
        s.metrics = numbers(j.at("metrics"), "metrics");
        s.baseline = numbers(j.value("baseline", json()), "baseline");
        for (const json& c : j.at("checks")) {
            Check k;
            k.metric = c.at("metric").get<std::string>();
            k.value = number(c.at("value"), "checks[].value");
            k.bound = c.at("bound").get<std::string>();
            k.limit = number(c.at("limit"), "checks[].limit");
            const auto st = statusFromString(c.at("status").get<std::string>());
            if (!st) throw bad("checks[].status is not pass, warn or fail");
            k.status = *st;
            k.message = c.value("message", "");
            k.where = c.value("where", "");
            if (c.contains("baseline")) k.baseline = number(c.at("baseline"), "checks[].baseline");
            s.checks.push_back(std::move(k));
        }
        const json renderers = j.value("renderers", json::object());
        for (const auto& [name, r] : renderers.items()) {
            RendererReport rr;
            rr.timingsMs = numbers(r.value("timings_ms", json()), "renderers." + name + ".timings_ms");
            rr.device = r.value("device", "");
            rr.counters = numbers(r.value("counters", json()), "renderers." + name + ".counters");
            rr.images = r.value("images", std::map<std::string, std::string>{});
            s.renderers[name] = std::move(rr);
        }
        const json maps = j.value("error_maps", json::object());
        for (const auto& [buffer, m] : maps.items())
            s.errorMaps[buffer] = {m.at("path").get<std::string>(), m.value("label", ""),
                                   number(m.at("lo"), "error_maps.lo"), number(m.at("hi"), "error_maps.hi"),
                                   m.value("unit", "")};
        s.settings = j.value("settings", json());
        s.error = j.value("error", "");
        return s;
    } catch (const json::exception& e) {
        throw bad(e.what());
    }
}

std::string reportPage(const std::string& title, const std::string& body, const std::string& createdAt,
                       const std::string& commandLine) {
    RunReport footer;
    footer.createdAt = createdAt;
    footer.commandLine = commandLine;
    return pageStart(title) + body + pageEnd(footer, "index.js", "");
}

std::string htmlEscape(std::string_view text) { return esc(text); }
std::string urlPath(std::string_view path) { return url(path); }

}  // namespace twinrender::compare
