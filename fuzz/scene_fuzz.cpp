// Fuzz target scene: a scene file and its --set overrides, as `render` reads them before any
// work (app::loadScene: the scene, both renderers' settings, [compare], the materials and,
// for scenes of a few particles, the particles). Input: the TOML text, then optionally a line
// "%%" and one KEY=VALUE override per line. A scene that loads names one folder inside the
// output folder, whatever its name.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "app/render_job.h"
#include "compare/thresholds.h"
#include "core/folder_name.h"
#include "core/particle_generators.h"
#include "core/scene.h"
#include "core/write_roots.h"
#include "fuzz/fuzz_support.h"

namespace {

// Scenes asking for more particles are a user's request for work, not a reader's bug: the
// target stops after parsing them. What a generated body asks for is what its shape needs at
// its lattice spacing, which a thin shell or ring (two layers at least) can make far more
// than its `particles` (a 0.1-thick ring 200 wide asking for 300 needs 77M).
constexpr std::int64_t MOST_PARTICLES = 2'000;

std::vector<std::string> overrideLines(const std::vector<std::string>& parts) {
    std::vector<std::string> lines;
    for (std::size_t p = 1; p < parts.size(); ++p) {
        std::size_t pos = 0;
        while (pos < parts[p].size()) {
            std::size_t end = parts[p].find('\n', pos);
            if (end == std::string::npos) end = parts[p].size();
            if (end > pos) lines.push_back(parts[p].substr(pos, end - pos));
            pos = end + 1;
        }
    }
    return lines;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace twinrender;
    const std::vector<std::string> parts = fuzz::splitParts(fuzz::asText(data, size));
    const auto file = fuzz::writeScratchFile("scene.toml", parts.front());
    const std::vector<std::string> overrides = overrideLines(parts);
    fuzz::expectCleanOutcome([&] {
        core::Scene scene = core::loadScene(file, overrides);
        const auto out = fuzz::scratchDir() / "out";
        if (!core::folderNameProblem(scene.name).empty() || out / scene.name == out ||
            !core::isInside(out, out / scene.name)) {
            std::fprintf(stderr, "scene name '%s' leads out of the output folder\n",
                         core::printable(scene.name).c_str());
            std::abort();
        }
        std::int64_t particles = 0;
        for (const core::BodyDesc& b : scene.bodies) {
            if (b.shape == core::Shape::File) {
                particles += MOST_PARTICLES;
                continue;
            }
            const double needed = core::expectedParticles(b);
            particles += needed < double(MOST_PARTICLES)
                             ? std::max<std::int64_t>(b.particles, std::llround(needed))
                             : MOST_PARTICLES + 1;
        }
        compare::sceneFileBounds(scene.compare);
        if (particles <= MOST_PARTICLES) app::loadScene(file, overrides);
    });
    return 0;
}
