// `twinrender export SCENE`: what another renderer needs to draw the scene's frames as the
// reference does (docs/external.md): the particles of every body as PLY (generated bodies too,
// every frame of a sequence), the camera as parameters and as view and projection matrices,
// the light, and each body's material with its textures baked to EXR images, described by one
// versioned JSON file. Everything is written into a staging folder and renamed into place.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/exit_code.h"
#include "app/render_job.h"

namespace twinrender::app {

struct ExportOptions {
    std::string scene;
    std::vector<std::string> sets;  // --set overrides
    std::string out = "out/export";
    std::string frames;  // "FIRST:LAST[:STEP]" of a sequence; empty: the scene's frame
};

// Writes OUT/<scene>/scene.json, OUT/<scene>/<frame>/particles.ply per frame and
// OUT/<scene>/textures/<material>.<slot>.exr. Throws core::InputError for bad input.
ExitCode runExport(const ExportOptions& options);

// The version of scene.json's format (its "version"), raised when a field changes meaning.
inline constexpr int EXPORT_FORMAT_VERSION = 1;

// scene.json's fields but "frames" and "camera", its textures baked under `dir`/textures/.
nlohmann::json sceneExportJson(const LoadedScene& scene, const std::filesystem::path& dir);
// One frame of the scene into `dir`/<frame>/particles.ply; its entry of "frames" (number,
// particle file relative to `dir`, count, camera).
nlohmann::json exportFrame(const LoadedScene& scene, std::int64_t frame,
                           const std::filesystem::path& dir);

}  // namespace twinrender::app
