#include "core/sequence.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numeric>

#include "core/error.h"

namespace twinrender::core {

namespace fs = std::filesystem;

namespace {

// The place of a body's path in messages: "scene.toml:30:1: body 'drop'".
std::string bodyWhere(const BodyDesc& b) {
    return fmt::format("{}: body '{}'", b.where, b.name);
}

glm::dvec3 unitOr(const ParameterTable& t, std::string_view key, glm::dvec3 fallback) {
    const glm::dvec3 v = t.getVec3(key, fallback);
    const double len = glm::length(v);
    if (!(len > 1e-12 && std::isfinite(len)))
        throw InputError(fmt::format("{} must be a non-zero vector", t.describe(key)));
    return v / len;
}

// Rodrigues' rotation of v about the unit axis by `radians`.
glm::dvec3 rotate(const glm::dvec3& v, const glm::dvec3& axis, double radians) {
    const double c = std::cos(radians), s = std::sin(radians);
    return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0 - c);
}

// Uniform Catmull-Rom through p1 and p2 (u in [0, 1]), p0 and p3 the neighbours.
glm::dvec3 catmullRom(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2,
                      const glm::dvec3& p3, double u) {
    const double u2 = u * u, u3 = u2 * u;
    return 0.5 * ((2.0 * p1) + (-p0 + p2) * u + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * u2 +
                  (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * u3);
}

void checkCamera(const CameraSettings& c, std::int64_t frame, const std::string& where) {
    const glm::dvec3 view = c.target - c.position;
    const double len = glm::length(view);
    if (!(len > 0.0 && std::isfinite(len)))
        throw InputError(fmt::format(
            "{}: at frame {} the camera's position and target coincide; move a key", where, frame));
    if (glm::length(glm::cross(view / len, c.up)) < 1e-6)
        throw InputError(fmt::format(
            "{}: at frame {} the camera looks along its 'up'; change camera.up or the path", where,
            frame));
    if (!(c.fovYDeg > 0.0 && c.fovYDeg <= 179.0))
        throw InputError(fmt::format("{}: at frame {} fov_y_deg is {}, outside (0, 179]", where,
                                     frame, c.fovYDeg));
}

CameraKey parseKey(const ParameterTable& t, const CameraSettings& camera) {
    CameraKey k;
    k.where = t.file();
    t.require("frame");
    k.frame = t.getDouble("frame", 0.0, -1e15, 1e15);
    t.require("position");
    k.position = t.getVec3("position", camera.position);
    k.target = t.getVec3("target", camera.target);
    k.fovYDeg = t.getDouble("fov_y_deg", camera.fovYDeg, 1e-6, 179.0);
    t.checkAllRead();
    return k;
}

// The frame numbers of a listed sequence within [first, last] and their greatest common step.
std::int64_t commonStep(const std::vector<FrameFile>& files, std::int64_t first,
                        std::int64_t last) {
    std::int64_t step = 0, previous = 0;
    bool any = false;
    for (const FrameFile& f : files) {
        if (f.number < first || f.number > last) continue;
        if (any) step = std::gcd(step, f.number - previous);
        previous = f.number;
        any = true;
    }
    return step > 0 ? step : 1;
}

}  // namespace

void resolveSequence(Scene& scene, const ParameterTable* table,
                     std::span<const ParameterTable> keys) {
    // The listed files of each body that names a sequence, by body index.
    std::vector<std::pair<std::size_t, FramePattern>> patterns;
    std::vector<std::vector<FrameFile>> listed;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const BodyDesc& b = scene.bodies[i];
        if (b.pattern.empty()) continue;
        auto pattern = FramePattern::parse(b.pattern, bodyWhere(b));
        patterns.emplace_back(i, *pattern);
        listed.push_back(pattern->list());
        if (listed.back().empty())
            throw InputError(fmt::format(
                "{}: no file matches the sequence {}; paths are relative to the scene file",
                bodyWhere(b), b.pattern.string()));
    }
    if (!table && patterns.empty()) {
        if (!keys.empty())
            throw InputError(
                fmt::format("{}: [[sequence.keys]] without a sequence", keys[0].file()));
        return;
    }

    SequenceSettings s;
    s.start = scene.camera;
    s.orbitAxis = scene.camera.up;
    const ParameterTable empty("sequence", scene.file.string());
    const ParameterTable& t = table ? *table : empty;
    s.where = table ? t.file() : scene.file.string();
    constexpr std::int64_t BIG = 1'000'000'000'000LL;
    const std::vector<FrameFile>* files = listed.empty() ? nullptr : &listed.front();
    if (!files && !t.has("last"))
        throw InputError(fmt::format(
            "{}: a sequence of generated bodies needs sequence.last (and sequence.first, "
            "default 0)",
            s.where));
    s.first = t.getInt("first", files ? files->front().number : 0, -BIG, BIG);
    s.last = t.getInt("last", files ? files->back().number : s.first, -BIG, BIG);
    if (s.last < s.first)
        throw InputError(fmt::format("{}: sequence.last ({}) is before sequence.first ({})",
                                     t.describe("last"), s.last, s.first));
    s.step = t.getInt("step", files ? commonStep(*files, s.first, s.last) : 1, 1, BIG);
    s.fps = t.getDouble("fps", s.fps, 1e-3, 1000.0);
    const std::string camera = t.getEnum("camera", "fixed", {"fixed", "orbit", "keys"});
    s.camera = camera == "orbit"  ? CameraPath::Orbit
               : camera == "keys" ? CameraPath::Keys
                                  : CameraPath::Fixed;
    if (s.camera == CameraPath::Orbit) {
        const bool perFrame = t.has("orbit.degrees_per_frame"), total = t.has("orbit.degrees");
        if (perFrame == total)
            throw InputError(fmt::format(
                "{}: camera = \"orbit\" needs one of orbit.degrees_per_frame and orbit.degrees "
                "(over the whole range)",
                t.describe("camera")));
        if (perFrame)
            s.orbitDegreesPerFrame = t.getDouble("orbit.degrees_per_frame", 0.0, -1e6, 1e6);
        else
            s.orbitDegreesPerFrame =
                s.last > s.first
                    ? t.getDouble("orbit.degrees", 0.0, -1e6, 1e6) / double(s.last - s.first)
                    : 0.0;
        s.orbitAxis = unitOr(t, "orbit.axis", scene.camera.up);
    }
    for (const ParameterTable& k : keys) s.keys.push_back(parseKey(k, scene.camera));
    if (s.camera == CameraPath::Keys) {
        if (s.keys.empty())
            throw InputError(fmt::format(
                "{}: camera = \"keys\" needs [[sequence.keys]] entries (frame, position, target)",
                t.describe("camera")));
        for (std::size_t i = 1; i < s.keys.size(); ++i)
            if (!(s.keys[i].frame > s.keys[i - 1].frame))
                throw InputError(
                    fmt::format("{}: key frames must be in ascending order of frame (frame {} "
                                "after {})",
                                s.keys[i].where, s.keys[i].frame, s.keys[i - 1].frame));
    } else if (!s.keys.empty()) {
        throw InputError(fmt::format("{}: [[sequence.keys]] are read with camera = \"keys\" only",
                                     s.keys.front().where));
    }
    if (table) t.checkAllRead();
    scene.sequence = s;

    // Every frame of the range has its file and a camera that can render it, before any work.
    const std::vector<std::int64_t> frames = sequenceFrames(scene);
    for (std::size_t p = 0; p < patterns.size(); ++p) {
        BodyDesc& b = scene.bodies[patterns[p].first];
        const FramePattern& pattern = patterns[p].second;
        for (std::int64_t n : frames) {
            const fs::path file = pattern.file(n, listed[p]);
            if (file.empty() || !fs::is_regular_file(file))
                throw InputError(fmt::format(
                    "{}: frame {} of the sequence {} is missing: {}; the scene asks for frames "
                    "{} to {} in steps of {}: add the file, or choose frames with --frames A:B "
                    "or [sequence] first, last and step",
                    bodyWhere(b), n, b.pattern.filename().string(),
                    file.empty() ? fmt::format("no file in {} matches it with the number {}",
                                               b.pattern.parent_path().string(), n)
                                 : file.string() + " does not exist",
                    s.first, s.last, s.step));
            b.frameFiles.push_back({n, file});
        }
    }
    for (std::int64_t n : frames) checkCamera(cameraAtFrame(scene, n), n, s.where);
    scene = frameScene(scene, s.first);
}

std::vector<std::int64_t> sequenceFrames(const Scene& scene) {
    if (!scene.sequence) return {scene.frame};
    std::vector<std::int64_t> frames;
    const SequenceSettings& s = *scene.sequence;
    for (std::int64_t n = s.first; n <= s.last; n += s.step) frames.push_back(n);
    return frames;
}

CameraSettings cameraAtFrame(const Scene& scene, std::int64_t frame) {
    if (!scene.sequence) return scene.camera;
    const SequenceSettings& s = *scene.sequence;
    CameraSettings c = s.start;
    if (s.camera == CameraPath::Orbit) {
        const double radians = s.orbitDegreesPerFrame * double(frame - s.first) * M_PI / 180.0;
        c.position = c.target + rotate(c.position - c.target, s.orbitAxis, radians);
        c.up = rotate(c.up, s.orbitAxis, radians);
    } else if (s.camera == CameraPath::Keys) {
        const auto& k = s.keys;
        const double f = double(frame);
        std::size_t i = 0;
        while (i + 1 < k.size() && k[i + 1].frame <= f) ++i;
        if (f <= k.front().frame || i + 1 >= k.size()) {
            const CameraKey& at = f <= k.front().frame ? k.front() : k.back();
            c.position = at.position;
            c.target = at.target;
            c.fovYDeg = at.fovYDeg;
        } else {
            const std::size_t i0 = i > 0 ? i - 1 : i, i3 = i + 2 < k.size() ? i + 2 : i + 1;
            const double u = (f - k[i].frame) / (k[i + 1].frame - k[i].frame);
            c.position =
                catmullRom(k[i0].position, k[i].position, k[i + 1].position, k[i3].position, u);
            c.target = catmullRom(k[i0].target, k[i].target, k[i + 1].target, k[i3].target, u);
            c.fovYDeg = k[i].fovYDeg + u * (k[i + 1].fovYDeg - k[i].fovYDeg);
        }
    }
    return c;
}

Scene frameScene(const Scene& scene, std::int64_t frame) {
    Scene out = scene;
    if (!scene.sequence) return out;
    const SequenceSettings& s = *scene.sequence;
    if (frame < s.first || frame > s.last || (frame - s.first) % s.step != 0)
        throw InputError(
            fmt::format("{}: frame {} is not one of the sequence's frames ({} to {} "
                        "in steps of {})",
                        s.where, frame, s.first, s.last, s.step));
    out.frame = frame;
    out.time = double(frame) / s.fps;
    out.camera = cameraAtFrame(scene, frame);
    for (BodyDesc& b : out.bodies)
        if (!b.pattern.empty())
            for (const FrameFile& f : b.frameFiles)
                if (f.number == frame) b.path = f.path;
    return out;
}

}  // namespace twinrender::core
