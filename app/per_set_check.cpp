#include "app/per_set_check.h"

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "app/build_identity.h"
#include "app/content_hash.h"
#include "core/image_io.h"
#include "realtime/gl/context.h"
#include "realtime/renderer.h"
#include "realtime/self_check.h"

namespace twinrender::app {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// TWINRENDER_SELF_CHECK_SOFTWARE=1 (a test hook): a software rasteriser is checked as any other
// device, so that the tests see the automatic check and its cache on llvmpipe.
bool checkSoftware() {
    const char* value = std::getenv("TWINRENDER_SELF_CHECK_SOFTWARE");
    return value != nullptr && std::string_view(value) == "1";
}

// What a remembered verdict holds for: the device, its driver, the real-time renderer's build.
json identity(const realtime::gl::Context& context) {
    return {{"device", context.renderer()},
            {"driver", context.version()},
            {"build", realtimeBuildIdentity()}};
}

// CACHE/self_check/<hash of identity()>.json.
fs::path verdictFile(const fs::path& cache, const json& what) {
    Hash h;
    h.add(what.dump());
    return cache / "self_check" / (h.hex() + ".json");
}

// The failed checks with their values, then (from the stages alone) the first stage apart.
std::string summary(const realtime::SelfCheck& check, const std::string& firstStage) {
    std::string out;
    for (const realtime::SelfCheck::Check& c : check.checks)
        if (!c.pass)
            out += fmt::format("{}{} cpu {:g} gpu {:g} (bound {:g})", out.empty() ? "" : ", ",
                               c.name, c.cpu, c.gpu, c.bound);
    if (!firstStage.empty()) out += "; first stage apart: " + firstStage;
    return out;
}

}  // namespace

void checkPerSetOnce(realtime::Device& device, const realtime::gl::Context& context,
                     const LoadedScene& scene, const SelfCheckPolicy& policy) {
    if (!policy.force && context.isSoftware() && !checkSoftware()) return;
    const json what = identity(context);
    const fs::path file = policy.cache.empty() ? fs::path() : verdictFile(policy.cache, what);
    std::error_code ec;
    if (!policy.force && !file.empty() && fs::exists(file, ec)) {
        std::ifstream in(file);
        const json remembered = json::parse(in, nullptr, /*allow_exceptions=*/false);
        if (remembered.is_object() && remembered.value("identity", json()) == what) {
            realtime::Device::PerSetCheck verdict{.passed = remembered.value("passed", false),
                                                  .summary = remembered.value("summary", "")};
            std::printf("per-set self-check on %s: %s (remembered in %s)\n",
                        context.renderer().c_str(), verdict.passed ? "pass" : "FAIL",
                        file.string().c_str());
            if (!verdict.passed)
                std::printf(
                    "  %s\n  the real-time renderer runs its per-set work on the CPU "
                    "(realtime.per_set_fallback = false keeps the GPU's)\n",
                    verdict.summary.c_str());
            std::fflush(stdout);
            device.setPerSetCheck(std::move(verdict));
            return;
        }
    }
    core::Scene small = scene.scene;
    small.camera.width = 160;
    small.camera.height = 120;
    const realtime::SelfCheck check =
        realtime::selfCheck(device, scene.realtime, {small, scene.particles, scene.materials});
    realtime::Device::PerSetCheck verdict{.passed = check.passed(), .summary = {}};
    if (verdict.passed) {
        std::printf("per-set self-check on %s (%s): pass\n", context.renderer().c_str(),
                    scene.scene.name.c_str());
    } else {
        context.makeCurrent();
        const realtime::SelfCheck stages = realtime::perSetStageCheck(
            scene.particles, scene.realtime, scene.scene.camera.position);
        verdict.summary = summary(check, realtime::firstStageApart(stages, ""));
        std::printf(
            "per-set self-check on %s (%s, per_set cpu against gpu): FAIL\n%s%s"
            "  the real-time renderer runs its per-set work on the CPU "
            "(realtime.per_set_fallback = false keeps the GPU's)\n",
            context.renderer().c_str(), scene.scene.name.c_str(), check.table().c_str(),
            verdict.summary.empty() ? "" : ("  " + verdict.summary + "\n").c_str());
    }
    std::fflush(stdout);
    if (!file.empty()) {
        fs::create_directories(file.parent_path());
        const json record = {{"identity", what},
                             {"scene", scene.scene.name},
                             {"passed", verdict.passed},
                             {"summary", verdict.summary},
                             {"table", check.table()}};
        core::writeTextFile(file, record.dump(2) + "\n");
    }
    device.setPerSetCheck(std::move(verdict));
}

}  // namespace twinrender::app
