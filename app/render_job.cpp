#include "app/render_job.h"

#include "app/progress.h"
#include "raymarch/renderer.h"

namespace twinrender::app {

LoadedScene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
    LoadedScene s;
    s.scene = core::loadScene(file, overrides);
    s.raymarch = raymarch::parseSettings(s.scene.raymarch);
    s.realtime = realtime::parseSettings(s.scene.realtime);
    // [compare.thresholds] belongs to compare/; its keys are read there.
    s.scene.compare.keysUnder("thresholds");
    s.scene.compare.checkAllRead();
    s.materials = core::loadMaterials(s.scene);
    s.particles = core::buildParticles(s.scene);
    return s;
}

Render renderRaymarch(const raymarch::EmbreeDevice& device, const LoadedScene& s, bool showProgress) {
    Progress progress(s.scene.name + ": raymarch");
    raymarch::Renderer renderer(device, s.scene, s.particles, s.materials, s.raymarch);
    Render r;
    r.frame = renderer.render([&](double f) {
        if (showProgress) progress.update(f);
    });
    progress.finish();
    r.display = core::tonemappedBeauty(r.frame.image, static_cast<float>(s.scene.camera.exposure));
    return r;
}

Render renderRealtime(realtime::Renderer& renderer, const LoadedScene& s) {
    realtime::RenderResult result = renderer.render(s.scene, s.particles, s.materials, s.realtime);
    return {std::move(result.frame), std::move(result.display)};
}

void writeRender(const LoadedScene& s, const Render& render, const std::filesystem::path& dir) {
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
    core::writeFrame(render.frame, render.display, dir, render.frame.renderer, extra);
}

}  // namespace twinrender::app
