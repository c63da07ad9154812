#include "app/export_command.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/output_folder.h"
#include "app/render_job.h"
#include "app/sequence_run.h"
#include "core/camera.h"
#include "core/derived_attributes.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/sequence.h"
#include "core/texture.h"

namespace twinrender::app {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json vec3Json(const glm::dvec3& v) {
    return json::array({v.x, v.y, v.z});
}

// A 4x4 matrix as rows (row-major: rows[r][c] is row r, column c; a point p maps to M p with p a
// column).
json rowsJson(const glm::dmat4& m) {
    json rows = json::array();
    for (int r = 0; r < 4; ++r) rows.push_back(json::array({m[0][r], m[1][r], m[2][r], m[3][r]}));
    return rows;
}

// OpenGL's perspective projection (gluPerspective): clip z in [-w, w] from near to far, the
// camera looking down -z.
glm::dmat4 projectionMatrix(const core::CameraSettings& c) {
    const double f = 1.0 / std::tan(0.5 * c.fovYDeg * 3.14159265358979323846 / 180.0);
    const double aspect = double(c.width) / c.height;
    glm::dmat4 p(0.0);
    p[0][0] = f / aspect;
    p[1][1] = f;
    p[2][2] = (c.far + c.near) / (c.near - c.far);
    p[3][2] = 2.0 * c.far * c.near / (c.near - c.far);
    p[2][3] = -1.0;
    return p;
}

json cameraJson(const core::CameraSettings& c) {
    const core::Camera camera(c);
    return {{"position", vec3Json(c.position)},
            {"target", vec3Json(c.target)},
            {"up", vec3Json(camera.up())},
            {"forward", vec3Json(camera.forward())},
            {"right", vec3Json(camera.right())},
            {"fov_y_deg", c.fovYDeg},
            {"near", c.near},
            {"far", c.far},
            {"width", c.width},
            {"height", c.height},
            {"exposure", c.exposure},
            {"view_matrix", rowsJson(camera.viewMatrix())},
            {"projection_matrix", rowsJson(projectionMatrix(c))}};
}

json lightJson(const core::LightSettings& l) {
    return {{"direction", vec3Json(l.direction)},
            {"intensity", l.intensity},
            {"color", vec3Json(l.color)},
            {"ambient", l.ambient},
            {"angular_radius_deg", l.angularRadiusDeg},
            {"ao_radius", l.aoRadius},
            {"emissive_light", l.emissiveLight}};
}

// Binary little-endian PLY of the particles: one vertex per particle with every attribute the
// renderers read (docs/external.md, "Particles").
void writePly(const core::SceneParticles& sp, const std::vector<core::Material>& materials,
              const fs::path& path) {
    const core::ParticleSet& ps = sp.particles;
    std::string header = fmt::format(
        "ply\nformat binary_little_endian 1.0\n"
        "comment twinrender export: positions, h and volume in scene units, normals world-space "
        "unit outward, albedo the diffuse texture at uv, glow emitted radiance (linear RGB)\n"
        "element vertex {}\n",
        ps.size());
    for (const char* p : {"x", "y", "z", "h", "volume"})
        header += fmt::format("property float {}\n", p);
    header += "property uint body\nproperty uint material\n";
    for (const char* p : {"u", "v", "nx", "ny", "nz", "albedo_r", "albedo_g", "albedo_b", "glow_r",
                          "glow_g", "glow_b", "temperature"})
        header += fmt::format("property float {}\n", p);
    header += "end_header\n";
    core::writeFileAtomically(path, [&](const fs::path& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        out.write(header.data(), static_cast<std::streamsize>(header.size()));
        std::vector<char> record;
        for (std::size_t i = 0; i < ps.size(); ++i) {
            record.clear();
            auto put = [&](const auto value) {
                const char* bytes = reinterpret_cast<const char*>(&value);
                record.insert(record.end(), bytes, bytes + sizeof(value));
            };
            const glm::vec3 albedo = materials.at(ps.material[i]).diffuse.sample(ps.uv[i]);
            for (float v :
                 {ps.position[i].x, ps.position[i].y, ps.position[i].z, ps.h[i], ps.volume[i]})
                put(v);
            put(ps.body[i]);
            put(ps.material[i]);
            for (float v : {ps.uv[i].x, ps.uv[i].y, ps.normal[i].x, ps.normal[i].y, ps.normal[i].z,
                            albedo.x, albedo.y, albedo.z, ps.glow[i].x, ps.glow[i].y, ps.glow[i].z,
                            i < ps.temperature.size() ? ps.temperature[i] : 0.0f})
                put(v);
            out.write(record.data(), static_cast<std::streamsize>(record.size()));
        }
        if (!out) throw core::InputError(fmt::format("{}: could not be written", path.string()));
    });
}

// The materials with their textures baked to linear EXR images (constants as 1 x 1 images).
json materialsJson(const std::vector<core::Material>& materials, const fs::path& dir) {
    json out = json::array();
    fs::create_directories(dir / "textures");
    for (std::size_t m = 0; m < materials.size(); ++m) {
        const core::Material& mat = materials[m];
        json j = {{"index", m}, {"name", mat.name}, {"shininess", mat.shininess}};
        const std::pair<const char*, const core::Texture*> slots[] = {
            {"diffuse", &mat.diffuse},
            {"specular", &mat.specular},
            {"emission", &mat.emission},
            {"city_lights", &mat.cityLights}};
        for (const auto& [slot, texture] : slots) {
            const std::string file = fmt::format("textures/{}.{}.exr", m, slot);
            core::writeImage(texture->image(), dir / file);
            j[slot] = file;
        }
        out.push_back(std::move(j));
    }
    return out;
}

json bodiesJson(const LoadedScene& s) {
    json out = json::array();
    for (std::size_t b = 0; b < s.particles.bodies.size(); ++b) {
        const core::BodyInfo& info = s.particles.bodies[b];
        json frame = json::array();
        for (int c = 0; c < 3; ++c) frame.push_back(vec3Json(info.frame[c]));
        out.push_back({{"index", b},
                       {"name", info.name},
                       {"material", info.material},
                       {"center", vec3Json(info.center)},
                       {"frame_columns", frame},
                       {"mean_h", info.meanH}});
    }
    return out;
}

}  // namespace

json sceneExportJson(const LoadedScene& s, const fs::path& staging) {
    return {{"format", "twinrender-export"},
            {"version", EXPORT_FORMAT_VERSION},
            {"scene", s.scene.name},
            {"source", s.scene.file.string()},
            {"conventions",
             {{"handedness", "right-handed world; the camera looks down -z in eye space"},
              {"units", "scene units for positions, h, depth and distances"},
              {"pixels",
               "row 0 at the top, pixel (x, y) covers [x, x+1) x [y, y+1), its "
               "centre at (x + 0.5, y + 0.5)"},
              {"depth", "Z: eye depth along the view axis, +inf where nothing is hit"},
              {"normals", "N: world space, unit, outward"},
              {"matrices",
               "row-major rows; OpenGL clip space (z in [-w, w]); "
               "docs/external.md gives Direct3D's, Unity's and Unreal's"},
              {"colour", "linear RGB radiance; the PNG is tonemapped with camera.exposure"}}},
            {"surface",
             {{"level", s.raymarch.surfaceLevel},
              {"kernel",
               "M4 cubic spline: W(r, h) = w(r/h) / (pi h^3), w(q) = 1 - 1.5 q^2 + "
               "0.75 q^3 below 1, 0.25 (2 - q)^3 below 2, 0 beyond"},
              {"field", "phi(x) = sum of volume_j W(|x - x_j|, h_j); the surface is phi = level"}}},
            {"light", lightJson(s.scene.light)},
            {"materials", materialsJson(s.materials, staging)},
            {"bodies", bodiesJson(s)}};
}

json exportFrame(const LoadedScene& scene, std::int64_t frame, const fs::path& staging) {
    LoadedScene s = scene;
    if (frame != scene.scene.frame) setFrame(s, frame);
    if (!s.particles.hasNormals) {
        core::deriveNormals(s.particles.particles, s.particles.bodies);
        s.particles.hasNormals = true;
    }
    const std::string folder = frameFolder(frame);
    fs::create_directories(staging / folder);
    writePly(s.particles, s.materials, staging / folder / "particles.ply");
    return {{"frame", frame},
            {"particles", folder + "/particles.ply"},
            {"particle_count", s.particles.particles.size()},
            {"camera", cameraJson(s.scene.camera)}};
}

ExitCode runExport(const ExportOptions& o) {
    std::vector<std::string> sets = o.sets;
    const LoadedScene first = loadScene(o.scene, sets);
    std::vector<std::int64_t> frames = {first.scene.frame};
    if (!o.frames.empty()) {
        if (!first.scene.sequence)
            throw core::InputError(
                fmt::format("{}: --frames {}: the scene is not a sequence", o.scene, o.frames));
        const std::vector<std::string> range = framesOverrides(o.frames);
        std::vector<std::string> ranged = sets;
        ranged.insert(ranged.end(), range.begin(), range.end());
        frames = core::sequenceFrames(loadScene(o.scene, ranged).scene);
    }
    const fs::path dir = fs::path(o.out) / first.scene.name;
    prepareOutputFolder(dir);
    writeTogether(dir, [&](const fs::path& staging) {
        json j = sceneExportJson(first, staging);
        json frameList = json::array();
        for (const std::int64_t frame : frames)
            frameList.push_back(exportFrame(first, frame, staging));
        j["frames"] = frameList;
        j["camera"] = frameList.front()["camera"];
        core::writeTextFile(staging / "scene.json", j.dump(2) + "\n");
    });
    std::printf("%s: %zu frame(s), %zu particles in the first -> %s\n", first.scene.name.c_str(),
                frames.size(), first.particles.particles.size(), (dir / "scene.json").c_str());
    return ExitCode::Pass;
}

}  // namespace twinrender::app
