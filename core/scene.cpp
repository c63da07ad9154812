#include "core/scene.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <set>

#include "core/error.h"
#include "core/folder_name.h"
#include "core/sequence.h"

namespace twinrender::core {
namespace fs = std::filesystem;

namespace {

// A --set KEY=VALUE applied to the document.
struct Override {
    std::string assignment;  // "bodies.planet.particles=5000"
    std::string key;         // "bodies.planet.particles", as the user wrote it
};
// By the path of the key from the document root, array entries by index
// ("bodies.0.particles").
using Overrides = std::map<std::string, Override>;

// Where a value came from, and its key as messages name it (empty: the parameter table's
// prefixed key).
struct Origin {
    std::string where;  // "file:line:column", the file, or "--set KEY=VALUE"
    std::string shownKey;
};

// The origin of the node at `fullKey`: the override that set it or a table around it (the
// innermost), else its place in the file. An override's nodes were parsed from its own text,
// so their lines and columns say nothing about the file.
Origin originOf(const std::string& file, const toml::node& node, const std::string& fullKey,
                const Overrides& overrides) {
    const Overrides::value_type* best = nullptr;
    for (const auto& entry : overrides) {
        const std::string& path = entry.first;
        const bool covers = fullKey == path || (fullKey.starts_with(path + "."));
        if (covers && (!best || path.size() > best->first.size())) best = &entry;
    }
    if (best)
        return {"--set " + best->second.assignment,
                best->second.key + fullKey.substr(best->first.size())};
    const auto& src = node.source();
    if (src.begin.line == 0) return {file, ""};
    return {fmt::format("{}:{}:{}", file, src.begin.line, src.begin.column), ""};
}

std::string whereOf(const std::string& file, const toml::node& node, const std::string& fullKey,
                    const Overrides& overrides) {
    return originOf(file, node, fullKey, overrides).where;
}

void flatten(const toml::table& table, const std::string& prefix, const std::string& fullPrefix,
             const std::string& file, const Overrides& overrides, ParameterTable& out);

// One node under the dotted `key`: a table's keys under it, or its value. `fullPrefix` is the
// key path from the document root to the table `key` is in, for locating --set overrides and
// for messages.
void flattenNode(const toml::node& node, const std::string& key, const std::string& fullPrefix,
                 const std::string& file, const Overrides& overrides, ParameterTable& out) {
    const std::string full = fullPrefix.empty() ? key : fullPrefix + "." + key;
    const auto [where, shown] = originOf(file, node, full, overrides);
    if (const auto* t = node.as_table()) {
        flatten(*t, key, fullPrefix, file, overrides, out);
    } else if (const auto* a = node.as_array()) {
        std::vector<double> values;
        for (const auto& e : *a) {
            if (auto d = e.value<double>())
                values.push_back(*d);
            else
                throw InputError(fmt::format("{}: key '{}' must be an array of numbers", where,
                                             shown.empty() ? full : shown));
        }
        out.set(key, std::move(values), where, shown);
    } else if (auto b = node.value_exact<bool>()) {
        out.set(key, *b, where, shown);
    } else if (auto i = node.value_exact<std::int64_t>()) {
        out.set(key, *i, where, shown);
    } else if (auto d = node.value_exact<double>()) {
        out.set(key, *d, where, shown);
    } else if (auto s = node.value_exact<std::string>()) {
        out.set(key, *s, where, shown);
    } else {
        throw InputError(
            fmt::format("{}: key '{}' has a type scenes do not use (dates and "
                        "times); use a number, string, boolean or array",
                        where, shown.empty() ? full : shown));
    }
}

// Flattens a TOML table into dotted keys (flattenNode).
void flatten(const toml::table& table, const std::string& prefix, const std::string& fullPrefix,
             const std::string& file, const Overrides& overrides, ParameterTable& out) {
    for (const auto& [k, node] : table)
        flattenNode(node,
                    prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str()),
                    fullPrefix, file, overrides, out);
}

std::vector<std::string> splitDots(const std::string& key) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (;;) {
        std::size_t dot = key.find('.', start);
        parts.push_back(key.substr(start, dot - start));
        if (dot == std::string::npos) break;
        start = dot + 1;
    }
    return parts;
}

// Stores VALUE under `key` in `table`, read as a TOML value; a bare word that is not TOML
// ("log") is stored as a string.
void assignOverrideValue(toml::table& table, const std::string& key, const std::string& value) {
    try {
        toml::table parsed = toml::parse("v = " + value);
        if (auto* n = parsed.get("v")) {
            n->visit([&](auto& x) { table.insert_or_assign(key, std::move(x)); });
            return;
        }
    } catch (const toml::parse_error&) {
    }
    table.insert_or_assign(key, value);
}

// Applies one --set KEY=VALUE to the document and records it under the path of its key.
// bodies.NAME.key and materials.NAME.key address the array entry by name (or by index).
void applyOverride(toml::table& root, const std::string& assignment, const std::string& file,
                   Overrides& overrides) {
    const auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
        throw InputError(
            fmt::format("--set {}: expected KEY=VALUE (e.g. camera.width=160)", assignment));
    const std::string key = assignment.substr(0, eq);
    const std::string value = assignment.substr(eq + 1);
    std::vector<std::string> parts = splitDots(key);
    // Every key the scene format has is a few names deep; an empty name ("a..b") or a key
    // thousands deep would only build tables that nothing reads.
    constexpr std::size_t MOST_DEPTH = 16;
    if (parts.size() > MOST_DEPTH ||
        std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); }))
        throw InputError(
            fmt::format("--set {}: not a key of the scene format (dotted names "
                        "such as camera.width, at most {} deep)",
                        key.substr(0, 80), MOST_DEPTH));
    toml::table* table = &root;
    std::size_t i = 0;
    std::string path = key;
    if ((parts[0] == "bodies" || parts[0] == "materials") && parts.size() >= 3) {
        auto* arr = root[parts[0]].as_array();
        toml::table* found = nullptr;
        std::size_t index = 0;
        if (arr)
            for (auto& e : *arr) {
                auto* t = e.as_table();
                const auto* name = t ? t->get_as<std::string>("name") : nullptr;
                if (t && ((name && name->get() == parts[1]) || std::to_string(index) == parts[1])) {
                    found = t;
                    path = parts[0] + "." + std::to_string(index) +
                           key.substr(parts[0].size() + 1 + parts[1].size());
                }
                ++index;
            }
        if (!found)
            throw InputError(fmt::format("--set {}: {} has no entry named '{}' in {}", assignment,
                                         parts[0], parts[1], file));
        table = found;
        i = 2;
    }
    for (; i + 1 < parts.size(); ++i) {
        auto* next = table->get(parts[i]);
        if (!next) {
            table->insert(parts[i], toml::table{});
            next = table->get(parts[i]);
        }
        if (!next->is_table())
            throw InputError(
                fmt::format("--set {}: '{}' is not a table in {}", assignment, parts[i], file));
        table = next->as_table();
    }
    assignOverrideValue(*table, parts.back(), value);
    overrides[path] = {assignment, key};
}

TextureSource parseTexture(const ParameterTable& t, std::string_view key, TextureSource fallback,
                           const fs::path& dir) {
    const ParameterTable::Entry* e = t.find(key);
    if (!e) return fallback;
    TextureSource src;
    src.where = t.describe(key);
    if (auto* d = std::get_if<double>(&e->value))
        src.value = glm::dvec3(*d);
    else if (auto* i = std::get_if<std::int64_t>(&e->value))
        src.value = glm::dvec3(double(*i));
    else if (auto* a = std::get_if<std::vector<double>>(&e->value)) {
        if (a->size() != 3)
            throw InputError(
                fmt::format("{} must be [r, g, b], a number, \"procedural:NAME\" or an "
                            "image path",
                            src.where));
        src.value = glm::dvec3((*a)[0], (*a)[1], (*a)[2]);
    } else if (auto* s = std::get_if<std::string>(&e->value)) {
        const std::string prefix = "procedural:";
        if (s->rfind(prefix, 0) == 0) {
            src.kind = TextureSource::Kind::Procedural;
            src.procedural = s->substr(prefix.size());
        } else {
            src.kind = TextureSource::Kind::File;
            src.path = fs::absolute(dir / *s).lexically_normal();
            std::error_code ec;
            const fs::file_status status = fs::status(src.path, ec);
            // A device such as /dev/zero would be read for ever.
            if (fs::exists(status) && !fs::is_regular_file(status))
                throw InputError(fmt::format(
                    "{}: texture {} is not a file (a device, pipe or folder); give an image file",
                    src.where, src.path.string()));
            if (!fs::is_regular_file(status))
                throw InputError(
                    fmt::format("{}: texture file {} does not exist; give a path "
                                "relative to the scene file",
                                src.where, src.path.string()));
        }
        return src;
    } else {
        throw InputError(
            fmt::format("{} must be [r, g, b], a number, \"procedural:NAME\" or an "
                        "image path",
                        src.where));
    }
    if (src.kind == TextureSource::Kind::Constant)
        for (int c = 0; c < 3; ++c)
            if (!(src.value[c] >= 0.0 && std::isfinite(src.value[c])))
                throw InputError(
                    fmt::format("{}: colour components must be finite and >= 0", src.where));
    return src;
}

glm::dvec3 unitVec3(const ParameterTable& t, std::string_view key, glm::dvec3 fallback) {
    glm::dvec3 v = t.getVec3(key, fallback);
    const double len = glm::length(v);
    if (!(len > 1e-12))
        throw InputError(fmt::format("{} must be a non-zero vector", t.describe(key)));
    return v / len;
}

TextureSource constantTexture(double v) {
    TextureSource s;
    s.value = glm::dvec3(v);
    return s;
}

MaterialDesc parseMaterial(const ParameterTable& t, const fs::path& dir) {
    MaterialDesc m;
    t.require("name");
    m.name = *t.findString("name");  // a name of another type is bad input naming the key
    m.diffuse = parseTexture(t, "diffuse", constantTexture(0.8), dir);
    m.specular = parseTexture(t, "specular", constantTexture(0.0), dir);
    m.emission = parseTexture(t, "emission", constantTexture(0.0), dir);
    m.cityLights = parseTexture(t, "city_lights", constantTexture(0.0), dir);
    m.shininess = t.getDouble("shininess", 32.0, 1.0, 10000.0);
    return m;
}

// bodies[].atmosphere.* (AtmosphereDesc), when any such key is given.
std::optional<AtmosphereDesc> parseAtmosphere(const ParameterTable& t) {
    bool given = false;
    for (const auto& [key, entry] : t.entries()) given = given || key.starts_with("atmosphere.");
    if (!given) return std::nullopt;
    const AtmosphereDesc d;
    AtmosphereDesc a;
    const double big = 1e15;
    a.thickness = t.getDouble("atmosphere.thickness", d.thickness, 0.0, big);
    a.scaleHeight = t.getDouble("atmosphere.scale_height", d.scaleHeight, 0.0, big);
    a.scattering = t.getVec3("atmosphere.scattering", d.scattering);
    a.absorption = t.getVec3("atmosphere.absorption", d.absorption);
    a.phaseG = t.getDouble("atmosphere.phase_g", d.phaseG, -0.99, 0.99);
    if (auto r = t.findDouble("atmosphere.radius")) {
        if (!(*r > 0.0 && *r < big))
            throw InputError(fmt::format("{} must be > 0", t.describe("atmosphere.radius")));
        a.radius = *r;
    }
    a.steps = static_cast<int>(t.getInt("atmosphere.steps", d.steps, 1, 256));
    for (const auto& [key, v] : {std::pair{"atmosphere.thickness", a.thickness},
                                 std::pair{"atmosphere.scale_height", a.scaleHeight}})
        if (!(v > 0.0)) throw InputError(fmt::format("{} must be > 0", t.describe(key)));
    for (int c = 0; c < 3; ++c)
        for (const auto& [key, v] : {std::pair{"atmosphere.scattering", a.scattering},
                                     std::pair{"atmosphere.absorption", a.absorption}})
            if (!(v[c] >= 0.0 && v[c] < big))
                throw InputError(fmt::format("{} must be >= 0 and finite", t.describe(key)));
    return a;
}

BodyDesc parseBody(const ParameterTable& t, const fs::path& dir,
                   const std::vector<MaterialDesc>& mats, std::size_t index) {
    BodyDesc b;
    b.where = t.file();
    b.name = t.getString("name", fmt::format("body{}", index));
    const std::string shape = t.getEnum("shape", "ball", {"ball", "shell", "ring", "file"});
    b.center = t.getVec3("center", glm::dvec3(0.0));
    b.material = t.getString("material", mats.empty() ? "" : mats.front().name);
    if (t.has("material") || !mats.empty()) {
        bool found = false;
        for (std::size_t m = 0; m < mats.size(); ++m)
            if (mats[m].name == b.material) {
                b.materialIndex = static_cast<std::uint32_t>(m);
                found = true;
            }
        if (!found) {
            std::string names;
            for (const auto& m : mats) names += (names.empty() ? "" : ", ") + m.name;
            throw InputError(
                fmt::format("{} names material '{}', which no [[materials]] entry "
                            "defines (defined: {})",
                            t.describe("material"), b.material, names.empty() ? "none" : names));
        }
    }
    b.temperature = t.getDouble("temperature", 0.0, 0.0, 1e6);
    b.atmosphere = parseAtmosphere(t);
    b.normal = unitVec3(t, "normal", glm::dvec3(0.0, 0.0, 1.0));
    if (auto s = t.findDouble("smoothing")) {
        if (!(*s > 0.0 && std::isfinite(*s)))
            throw InputError(fmt::format("{} must be > 0", t.describe("smoothing")));
        b.smoothing = *s;
    }
    const double big = 1e15;
    if (shape == "file") {
        b.shape = Shape::File;
        const auto& p = t.require("path");
        auto* s = std::get_if<std::string>(&p.value);
        if (!s) throw InputError(fmt::format("{} must be a string", t.describe("path")));
        if (t.has("velocity") || t.has("spin") || t.has("churn"))
            throw InputError(fmt::format(
                "{}: velocity, spin and churn move generated bodies; a file body moves by its "
                "frames (a path such as out_%04d.ssf names a sequence)",
                t.describe(t.has("velocity") ? "velocity"
                           : t.has("spin")   ? "spin"
                                             : "churn")));
        const fs::path given = fs::absolute(dir / *s).lexically_normal();
        if (FramePattern::parse(given, t.describe("path")))
            b.pattern = given;  // its files are listed and checked by resolveSequence
        else
            b.path = given;
        if (b.pattern.empty() && !fs::is_regular_file(b.path))
            throw InputError(
                fmt::format("{}: particle file {} does not exist; paths are relative "
                            "to the scene file",
                            t.describe("path"), b.path.string()));
        b.scale = t.getDouble("scale", 1.0, 1e-30, 1e30);
        if (!(b.scale > 0.0)) throw InputError(fmt::format("{} must be > 0", t.describe("scale")));
    } else {
        b.particles = t.getInt("particles", 1000, 1, 50'000'000);
        b.lattice = [&] {
            std::string l = t.getEnum("lattice", "hcp", {"hcp", "cubic", "random"});
            return l == "hcp" ? Lattice::Hcp : l == "cubic" ? Lattice::Cubic : Lattice::Random;
        }();
        b.seed = static_cast<std::uint64_t>(
            t.getInt("seed", 1, 0, std::numeric_limits<std::int64_t>::max()));
        b.velocity = t.getVec3("velocity", b.velocity);
        b.spin = t.getVec3("spin", b.spin);
        b.churn = t.getDouble("churn", 0.0, 0.0, 1e3);
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(b.velocity[c]) || !std::isfinite(b.spin[c]))
                throw InputError(
                    fmt::format("{} must be finite",
                                t.describe(std::isfinite(b.velocity[c]) ? "spin" : "velocity")));
        if (shape == "ring") {
            b.shape = Shape::Ring;
            b.innerRadius = t.getDouble("inner_radius", 0.0, 0.0, big);
            t.require("outer_radius");
            b.outerRadius = t.getDouble("outer_radius", 0.0, 0.0, big);
            b.thickness = t.getDouble("thickness", 0.0, 0.0, big);
            if (!(b.outerRadius > b.innerRadius))
                throw InputError(
                    fmt::format("{} must be larger than inner_radius", t.describe("outer_radius")));
            if (!(b.thickness > 0.0))
                throw InputError(
                    fmt::format("{}: a ring needs thickness > 0", t.describe("thickness")));
        } else {
            b.shape = shape == "ball" ? Shape::Ball : Shape::Shell;
            b.radius = t.getDouble("radius", 1.0, 0.0, big);
            if (!(b.radius > 0.0))
                throw InputError(fmt::format("{} must be > 0", t.describe("radius")));
            if (b.shape == Shape::Shell) {
                b.thickness = t.getDouble("thickness", 0.1 * b.radius, 0.0, b.radius);
                if (!(b.thickness > 0.0))
                    throw InputError(
                        fmt::format("{}: a shell needs thickness > 0", t.describe("thickness")));
            }
        }
    }
    return b;
}

}  // namespace

Scene loadScene(const fs::path& path, std::span<const std::string> overrides) {
    const fs::path file = fs::absolute(path).lexically_normal();
    const std::string fileName = path.string();
    if (!fs::is_regular_file(file))
        throw InputError(
            fmt::format("{}: scene file not found; give the path of a .toml scene", fileName));
    toml::table root;
    try {
        root = toml::parse_file(file.string());
    } catch (const toml::parse_error& e) {
        throw InputError(fmt::format("{}:{}:{}: TOML syntax error: {}", fileName,
                                     e.source().begin.line, e.source().begin.column,
                                     e.description()));
    }
    Overrides located;
    for (const auto& o : overrides) applyOverride(root, o, fileName, located);

    Scene scene;
    scene.file = file;
    const fs::path dir = file.parent_path();

    // Top-level scalars and sections.
    ParameterTable top("", fileName);
    std::vector<std::pair<std::string, const toml::array*>> arrays;
    for (const auto& [k, node] : root) {
        const std::string key(k.str());
        if (key == "materials" || key == "bodies") {
            const auto* a = node.as_array();
            if (!a || !a->is_array_of_tables())
                throw InputError(fmt::format("{}: '{}' must be an array of tables ([[{}]])",
                                             whereOf(fileName, node, key, located), key, key));
            arrays.emplace_back(key, a);
            continue;
        }
        if (!node.is_table()) {
            if (key == "sequence")
                throw InputError(fmt::format("{}: 'sequence' must be a table ([sequence])",
                                             whereOf(fileName, node, key, located)));
            flattenNode(node, key, "", fileName, located, top);
        }
    }
    scene.name = top.getString("name", file.stem().string());
    // The name names the scene's output folder: it must be one folder name everywhere
    // (folder_name.h), never a path that leads out of the output folder.
    if (const std::string problem = folderNameProblem(scene.name); !problem.empty())
        throw InputError(
            top.has("name")
                ? fmt::format("{}: '{}' {}; {}", top.describe("name"), printable(scene.name),
                              problem, folderNameRule())
                : fmt::format("{}: the scene has no 'name', and its file's name '{}' {}; add a "
                              "name = \"...\" line ({})",
                              fileName, printable(scene.name), problem, folderNameRule()));
    scene.description = top.getString("description", "");
    top.checkAllRead();

    auto section = [&](const std::string& name) {
        ParameterTable t(name, fileName);
        for (const auto& [k, node] : root) {
            if (std::string(k.str()) != name) continue;
            if (!node.is_table())
                throw InputError(fmt::format("{}: '{}' must be a table ([{}])",
                                             whereOf(fileName, node, name, located), name, name));
            flatten(*node.as_table(), "", name, fileName, located, t);
        }
        return t;
    };
    std::set<std::string> known = {"name",   "description", "camera",   "light",   "materials",
                                   "bodies", "realtime",    "raymarch", "compare", "sequence"};
    for (const auto& [k, node] : root)
        if (node.is_table() && !known.count(std::string(k.str())))
            throw InputError(
                fmt::format("{}: unknown table '[{}]'; scene files have [camera], "
                            "[light], [[materials]], [[bodies]], [realtime], "
                            "[raymarch], [compare] and [sequence]",
                            whereOf(fileName, node, std::string(k.str()), located), k.str()));

    {
        ParameterTable t = section("camera");
        CameraSettings& c = scene.camera;
        c.position = t.getVec3("position", c.position);
        c.target = t.getVec3("target", c.target);
        c.up = unitVec3(t, "up", c.up);
        c.fovYDeg = t.getDouble("fov_y_deg", c.fovYDeg, 1e-6, 179.0);
        c.near = t.getDouble("near", c.near, 1e-30, 1e30);
        c.far = t.getDouble("far", c.far, 1e-30, 1e38);
        c.width = static_cast<int>(t.getInt("width", c.width, 1, 16384));
        c.height = static_cast<int>(t.getInt("height", c.height, 1, 16384));
        c.exposure = t.getDouble("exposure", c.exposure, 1e-6, 1e6);
        if (!(c.near > 0.0 && c.far > c.near))
            throw InputError(fmt::format("{}: camera needs 0 < near < far (near = {}, far = {})",
                                         t.describe("far"), c.near, c.far));
        if (static_cast<double>(c.width) * c.height > 64.0 * 1024 * 1024)
            throw InputError(
                fmt::format("{}: {}x{} pixels is more than the 64 Mpixel limit; use a "
                            "smaller resolution",
                            t.describe("width"), c.width, c.height));
        const glm::dvec3 view = c.target - c.position;
        if (!(glm::length(view) > 0.0))
            throw InputError(
                fmt::format("{}: camera position and target coincide", t.describe("target")));
        if (glm::length(glm::cross(view / glm::length(view), c.up)) < 1e-6)
            throw InputError(
                fmt::format("{}: 'up' is parallel to the view direction", t.describe("up")));
        t.checkAllRead();
    }
    {
        ParameterTable t = section("light");
        LightSettings& l = scene.light;
        l.direction = unitVec3(t, "direction", l.direction);
        l.intensity = t.getDouble("intensity", l.intensity, 0.0, 1e9);
        l.color = t.getVec3("color", l.color);
        l.ambient = t.getDouble("ambient", l.ambient, 0.0, 1e9);
        l.angularRadiusDeg = t.getDouble("angular_radius", l.angularRadiusDeg, 0.0, 10.0);
        l.aoRadius = t.getDouble("ao_radius", l.aoRadius, 0.0, 1e9);
        l.emissiveLight = t.getBool("emissive_light", l.emissiveLight);
        for (int c = 0; c < 3; ++c)
            if (!(l.color[c] >= 0.0))
                throw InputError(fmt::format("{} must be >= 0", t.describe("color")));
        t.checkAllRead();
    }
    for (const auto& [key, arr] : arrays) {
        if (key != "materials") continue;
        std::size_t i = 0;
        for (const auto& node : *arr) {
            ParameterTable t(fmt::format("materials[{}]", i),
                             whereOf(fileName, node, key, located));
            flatten(*node.as_table(), "", fmt::format("materials.{}", i), fileName, located, t);
            scene.materials.push_back(parseMaterial(t, dir));
            t.checkAllRead();
            for (std::size_t j = 0; j + 1 < scene.materials.size(); ++j)
                if (scene.materials[j].name == scene.materials.back().name)
                    throw InputError(fmt::format("{}: material name '{}' is used twice", t.file(),
                                                 scene.materials.back().name));
            ++i;
        }
    }
    if (scene.materials.empty()) {
        MaterialDesc m;
        m.name = "default";
        m.diffuse = constantTexture(0.8);
        m.specular = m.emission = m.cityLights = constantTexture(0.0);
        scene.materials.push_back(m);
    }
    for (const auto& [key, arr] : arrays) {
        if (key != "bodies") continue;
        std::size_t i = 0;
        for (const auto& node : *arr) {
            ParameterTable t(fmt::format("bodies[{}]", i), whereOf(fileName, node, key, located));
            flatten(*node.as_table(), "", fmt::format("bodies.{}", i), fileName, located, t);
            scene.bodies.push_back(parseBody(t, dir, scene.materials, i));
            t.checkAllRead();
            if (scene.bodies.back().atmosphere)
                for (std::size_t j = 0; j + 1 < scene.bodies.size(); ++j)
                    if (scene.bodies[j].atmosphere)
                        throw InputError(fmt::format(
                            "{}: bodies '{}' and '{}' both have an atmosphere; a scene has one "
                            "at most",
                            t.describe("atmosphere"), scene.bodies[j].name,
                            scene.bodies.back().name));
            ++i;
        }
    }
    if (scene.bodies.empty())
        throw InputError(
            fmt::format("{}: the scene has no [[bodies]]; add at least one", fileName));
    // [sequence], its [[sequence.keys]] read apart (an array of tables, not of numbers).
    std::optional<ParameterTable> sequence;
    std::vector<ParameterTable> keys;
    if (const toml::node* node = root.get("sequence"); node && node->is_table()) {
        toml::table t = *node->as_table();
        if (const toml::node* k = t.get("keys")) {
            const auto* a = k->as_array();
            if (!a || !a->is_array_of_tables())
                throw InputError(fmt::format(
                    "{}: 'sequence.keys' must be an array of tables ([[sequence.keys]])",
                    whereOf(fileName, *k, "sequence.keys", located)));
            std::size_t i = 0;
            for (const auto& entry : *a) {
                ParameterTable kt(fmt::format("sequence.keys[{}]", i),
                                  whereOf(fileName, entry, "sequence.keys", located));
                flatten(*entry.as_table(), "", fmt::format("sequence.keys.{}", i), fileName,
                        located, kt);
                keys.push_back(std::move(kt));
                ++i;
            }
            t.erase("keys");
        }
        sequence.emplace("sequence", whereOf(fileName, *node, "sequence", located));
        flatten(t, "", "sequence", fileName, located, *sequence);
    }
    resolveSequence(scene, sequence ? &*sequence : nullptr, keys);
    scene.realtime = section("realtime");
    scene.raymarch = section("raymarch");
    scene.compare = section("compare");
    return scene;
}

}  // namespace twinrender::core
