// Loading a scene and rendering it with either renderer: what every command that renders
// shares. All input is read and checked before any rendering starts.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/frame.h"
#include "core/particles.h"
#include "core/scene.h"
#include "core/texture.h"
#include "raymarch/embree_device.h"
#include "raymarch/settings.h"
#include "realtime/renderer.h"
#include "realtime/settings.h"

namespace twinrender::app {

// A scene with everything both renderers need, validated.
struct LoadedScene {
    core::Scene scene;
    raymarch::Settings raymarch;
    realtime::Settings realtime;
    std::vector<core::Material> materials;
    core::SceneParticles particles;
};

// Reads the scene, applies the overrides, parses every renderer section (unknown keys are
// errors), loads the textures and builds the particles.
LoadedScene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides);

// A rendered frame and the image a person looks at (tonemapped; bloom when enabled).
struct Render {
    core::Frame frame;
    core::Image display;
};

// Renders with the reference raymarcher.
Render renderRaymarch(const raymarch::EmbreeDevice& device, const LoadedScene& scene,
                      bool showProgress);

// Renders with the real-time renderer (its GL context is current on this thread).
Render renderRealtime(realtime::Renderer& renderer, const LoadedScene& scene);

// Writes DIR/<renderer>.exr|.png|.json for a frame of the scene.
void writeRender(const LoadedScene& scene, const Render& render, const std::filesystem::path& dir);

}  // namespace twinrender::app
