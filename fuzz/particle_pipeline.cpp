#include "fuzz/particle_pipeline.h"

#include "core/particles.h"
#include "core/scene.h"
#include "core/texture.h"
#include "fuzz/fuzz_support.h"
#include "raymarch/embree_device.h"
#include "raymarch/renderer.h"
#include "realtime/anisotropy.h"
#include "realtime/impostor_radius.h"
#include "realtime/occlusion_culling.h"
#include "realtime/occlusion_spheres.h"

namespace twinrender::fuzz {

namespace {

// One body read from `path`, seen by the default camera at a size that keeps a frame to a
// few milliseconds.
core::Scene fileScene(const std::filesystem::path& path) {
    core::Scene scene;
    scene.name = "fuzz";
    scene.file = scratchDir() / "scene.toml";
    scene.camera.width = 16;
    scene.camera.height = 12;
    core::MaterialDesc material;
    material.name = "m";
    material.diffuse.value = glm::dvec3(0.5);
    scene.materials.push_back(material);
    core::BodyDesc body;
    body.name = "file";
    body.shape = core::Shape::File;
    body.path = path;
    body.material = "m";
    body.where = "fuzz scene";
    scene.bodies.push_back(body);
    return scene;
}

const raymarch::EmbreeDevice& embreeDevice() {
    static const raymarch::EmbreeDevice device;
    return device;
}

}  // namespace

void runParticlePipeline(std::string_view bytes, const std::string& extension) {
    const std::filesystem::path path = writeScratchFile("particles" + extension, bytes);
    expectCleanOutcome([&] {
        const core::Scene scene = fileScene(path);
        core::SceneParticles particles = core::buildParticles(scene);
        // The normals, as the real-time renderer's CPU path derives them (their neighbour
        // grids are where a corrupted snapshot once hung).
        core::deriveNormals(particles);
        const std::vector<core::Material> materials = core::loadMaterials(scene);

        const realtime::ParticleSettings particleSettings;
        const std::vector<float> radii =
            realtime::impostorRadii(particles.particles, particleSettings);
        realtime::unoccludedParticles(particles.particles, radii);
        realtime::anisotropicEllipsoids(particles.particles, radii, {});
        realtime::occlusionSpheres(particles);

        raymarch::Renderer renderer(embreeDevice(), raymarch::Settings{});
        renderer.render(core::RenderInput{scene, particles, materials});
    });
}

}  // namespace twinrender::fuzz
