#include "app/render_job.h"

#include "app/progress.h"
#include "raymarch/renderer.h"

namespace twinrender::app {

LoadedScene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
    LoadedScene s;
    s.scene = core::loadScene(file, overrides);
    s.raymarch = raymarch::parseSettings(s.scene.raymarch);
    // [compare.thresholds] belongs to compare/; its keys are read there.
    s.scene.compare.keysUnder("thresholds");
    s.scene.compare.checkAllRead();
    s.materials = core::loadMaterials(s.scene);
    s.particles = core::buildParticles(s.scene);
    return s;
}

core::Frame renderRaymarch(const raymarch::EmbreeDevice& device, const LoadedScene& s,
                           bool showProgress) {
    Progress progress(s.scene.name + ": raymarch");
    raymarch::Renderer renderer(device, s.scene, s.particles, s.materials, s.raymarch);
    core::Frame frame = renderer.render([&](double f) {
        if (showProgress) progress.update(f);
    });
    progress.finish();
    return frame;
}

void writeRender(const LoadedScene& s, const core::Frame& frame, const std::filesystem::path& dir) {
    nlohmann::json extra;
    extra["scene"] = s.scene.name;
    extra["scene_file"] = s.scene.file.string();
    extra["camera"] = {{"position", {s.scene.camera.position.x, s.scene.camera.position.y,
                                     s.scene.camera.position.z}},
                       {"target", {s.scene.camera.target.x, s.scene.camera.target.y,
                                   s.scene.camera.target.z}},
                       {"fov_y_deg", s.scene.camera.fovYDeg},
                       {"near", s.scene.camera.near},
                       {"far", s.scene.camera.far},
                       {"exposure", s.scene.camera.exposure}};
    const core::Image display =
        core::tonemappedBeauty(frame.image, static_cast<float>(s.scene.camera.exposure));
    core::writeFrame(frame, display, dir, frame.renderer, extra);
}

}  // namespace twinrender::app
