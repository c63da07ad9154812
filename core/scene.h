// The scene model (docs/scenes.md) and its parser. A scene is one TOML file; every key
// is read in exactly one place (scene.cpp) and any unknown key is an error naming the file,
// line and key. Renderer sections ([realtime], [raymarch]) stay as parameter tables: each
// renderer parses its own settings from them and reports the keys it did not read.
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/vec3.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/frame_pattern.h"
#include "core/parameters.h"

namespace twinrender::core {

struct CameraSettings {
    glm::dvec3 position{0.0, -6.0, 1.5};  // scene units
    glm::dvec3 target{0.0, 0.0, 0.0};     // scene units
    glm::dvec3 up{0.0, 0.0, 1.0};         // need not be orthogonal to the view direction
    double fovYDeg = 40.0;                // vertical field of view, degrees, (0, 179]
    double near = 0.05;                   // scene units, > 0
    double far = 100.0;                   // scene units, > near
    int width = 640;                      // pixels, 1..16384
    int height = 360;                     // pixels, 1..16384
    double exposure = 1.0;                // multiplies radiance before the tonemapper, > 0
};

struct LightSettings {
    glm::dvec3 direction{-1.0, 0.4, -0.3};  // unit after parsing; the way light travels
    double intensity = 3.0;                 // irradiance scale, >= 0
    glm::dvec3 color{1.0, 1.0, 1.0};        // linear RGB, >= 0
    double ambient = 0.03;                  // ambient fraction of the diffuse albedo, >= 0
    // Angular radius of the sun's disc, degrees, [0, 10]; 0: a point direction (hard shadows).
    // The reference averages the visibility over sun directions across the disc; the real-time
    // "pcf" widens its filter to the penumbra (realtime/shaders/shade.frag).
    double angularRadiusDeg = 0.0;
    // The reach R of ambient occlusion, scene units, >= 0; 0: no occlusion (the ambient term
    // everywhere). Both renderers read it: the reference traces cosine-weighted rays of length
    // R (raymarch/ao_hemisphere.h), the real-time renderer's screen-space pass
    // (realtime.ao.method) looks this far.
    double aoRadius = 0.0;
    // Light cast by emitting surfaces (emission maps, blackbody glow) onto the others: the
    // irradiance E from them, added by the shared shading as albedo * E / pi. Both renderers
    // read it: the reference integrates E over the emitting bodies by Monte Carlo
    // (raymarch.emissive_samples), the real-time renderer estimates it with
    // realtime.emissive.method. false: no such light (E = 0).
    bool emissiveLight = false;
};

// Where a texture comes from: a constant colour, a named procedural, or an image file.
struct TextureSource {
    enum class Kind { Constant, Procedural, File };
    Kind kind = Kind::Constant;
    glm::dvec3 value{0.0};       // Constant: linear RGB
    std::string procedural;      // Procedural: the name after "procedural:"
    std::filesystem::path path;  // File: absolute (resolved against the scene file)
    std::string where;           // "file:line:col: key 'materials[earth].diffuse'"
};

struct MaterialDesc {
    std::string name;
    TextureSource diffuse;     // albedo, linear RGB
    TextureSource specular;    // specular colour, linear RGB
    TextureSource emission;    // emitted radiance, linear RGB
    TextureSource cityLights;  // emitted radiance on the night side only
    double shininess = 32.0;   // Blinn-Phong exponent, [1, 10000]
};

enum class Shape { Ball, Shell, Ring, File };

// A thin scattering shell around a body (bodies[].atmosphere.*, core/atmosphere.h): between the
// body's surface sphere and that sphere grown by `thickness`, with a density that falls
// exponentially with the height above the inner sphere. Coefficients are per scene unit at the
// inner sphere.
struct AtmosphereDesc {
    double thickness = 0.1;                // atmosphere.thickness: scene units, > 0
    double scaleHeight = 0.03;             // atmosphere.scale_height: scene units, > 0
    glm::dvec3 scattering{0.6, 1.4, 3.3};  // atmosphere.scattering: per scene unit, >= 0
    glm::dvec3 absorption{0.0};            // atmosphere.absorption: per scene unit, >= 0
    double phaseG = 0.0;  // atmosphere.phase_g: Henyey-Greenstein asymmetry, [-0.99, 0.99]
    // atmosphere.radius: the inner sphere's radius, scene units; unset: the body's level-set
    // radius (core/body_sphere.h, levelSetRadius).
    std::optional<double> radius;
    int steps = 32;  // atmosphere.steps: quadrature steps along a view ray and a sun path, 1..256
};
enum class Lattice { Hcp, Cubic, Random };

struct BodyDesc {
    std::string name;
    Shape shape = Shape::Ball;
    glm::dvec3 center{0.0};            // scene units
    double radius = 1.0;               // ball/shell: outer radius, scene units
    glm::dvec3 normal{0.0, 0.0, 1.0};  // ring: plane normal; all shapes: the uv pole axis
    double innerRadius = 0.0;          // ring: scene units
    double outerRadius = 0.0;          // ring: scene units
    double thickness = 0.0;            // ring: full thickness; shell: wall thickness
    std::int64_t particles = 1000;     // approximate count for generators, >= 1
    Lattice lattice = Lattice::Hcp;
    std::uint64_t seed = 1;
    std::string material;             // a name from [[materials]]
    std::uint32_t materialIndex = 0;  // resolved index into Scene::materials
    double temperature = 0.0;         // kelvin, >= 0; overridden by a file's column
    std::optional<double> smoothing;  // h in scene units; default 1.3 x lattice spacing
    std::filesystem::path path;       // file: absolute path of the particle file (of the
                                      // scene's frame when the path names a sequence)
    // file: the sequence pattern (absolute) when the path names one (core/frame_pattern.h),
    // and the file of every frame of the scene's range; empty otherwise.
    std::filesystem::path pattern;
    std::vector<FrameFile> frameFiles;
    // Motion of a generated body over a sequence (core/body_motion.h), at time t = frame / fps:
    glm::dvec3 velocity{0.0};  // scene units per second
    glm::dvec3 spin{0.0};      // angular velocity about the centre: degrees per second about
                               // the vector's direction (right-handed)
    double churn = 0.0;        // a new random displacement each frame, up to churn x h, >= 0
    double scale = 1.0;        // file: multiplies positions and smoothing lengths
    // atmosphere.*: the body's scattering shell; at most one body of a scene has one.
    std::optional<AtmosphereDesc> atmosphere;
    std::string where;  // "file:line" of the [[bodies]] entry, for messages
};

// How the camera moves over a sequence.
enum class CameraPath { Fixed, Orbit, Keys };

struct CameraKey {
    double frame = 0.0;  // frame number
    glm::dvec3 position{0.0};
    glm::dvec3 target{0.0};
    double fovYDeg = 40.0;
    std::string where;  // "file:line:col" of the [[sequence.keys]] entry
};

// The [sequence] table (core/sequence.h): which frames, how fast, and the camera's path.
struct SequenceSettings {
    std::int64_t first = 0;  // frame numbers, first <= last
    std::int64_t last = 0;
    std::int64_t step = 1;  // >= 1
    double fps = 24.0;      // frames per second of sequence time and of the video, (0, 1000]
    CameraPath camera = CameraPath::Fixed;
    // orbit: about orbitAxis (unit, through camera.target), from [camera] at frame `first`.
    double orbitDegreesPerFrame = 0.0;
    glm::dvec3 orbitAxis{0.0, 0.0, 1.0};
    std::vector<CameraKey> keys;  // keys: by ascending frame, interpolated (Catmull-Rom)
    CameraSettings start;         // the camera as [camera] gives it
    std::string where;            // "file:line:col" of [sequence] (or the file)
};

struct Scene {
    std::string name;  // default: the file's stem
    std::string description;
    std::filesystem::path file;  // the scene file (absolute)
    CameraSettings camera;
    LightSettings light;
    std::vector<MaterialDesc> materials;
    std::vector<BodyDesc> bodies;
    ParameterTable realtime;  // [realtime], parsed by realtime/
    ParameterTable raymarch;  // [raymarch], parsed by raymarch/
    ParameterTable compare;   // [compare], parsed by compare/
    // Set when the scene is a sequence: a [sequence] table or a file body naming a sequence.
    std::optional<SequenceSettings> sequence;
    // The frame the camera and the bodies stand at (a sequence's first frame after loading;
    // core/sequence.h frameScene moves it) and its time in seconds, frame / fps.
    std::int64_t frame = 0;
    double time = 0.0;
};

// Loads a scene file. `overrides` are "KEY=VALUE" strings with the scene's dotted keys
// (camera.width=160, realtime.ssss.enabled=false, bodies.planet.particles=5000); VALUE is
// read as TOML, or as a plain string when it is not valid TOML. Throws InputError with the
// file, line and key for syntax errors, unknown keys, wrong types, missing required keys,
// unknown materials and out-of-range values.
Scene loadScene(const std::filesystem::path& file, std::span<const std::string> overrides = {});

}  // namespace twinrender::core
