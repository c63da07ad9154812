#include "app/external_renderer.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/export_command.h"
#include "app/sequence_run.h"
#include "app/test_images.h"
#include "core/cancellation.h"
#include "core/error.h"
#include "core/frame.h"
#include "core/image_io.h"

namespace twinrender::app {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The last `lines` lines of a text file.
std::string lastLines(const fs::path& file, int lines) {
    std::ifstream in(file);
    std::vector<std::string> all;
    for (std::string line; std::getline(in, line);) all.push_back(line);
    std::string out;
    for (std::size_t i = all.size() > std::size_t(lines) ? all.size() - lines : 0; i < all.size();
         ++i)
        out += "\n    " + all[i];
    return out.empty() ? " (nothing on standard error)" : out;
}

struct CommandRun {
    int exitCode = 0;
    bool timedOut = false;
    double seconds = 0.0;
};

// Runs `command` "$request" through /bin/sh in `folder` (`request` relative to it), its own process
// group, standard output and error into folder/stdout.log and stderr.log; ends the group at the
// time limit or when `cancel` is set.
CommandRun runCommand(const std::string& command, const fs::path& request, const fs::path& folder,
                      double timeoutSeconds, const std::atomic<bool>* cancel) {
    const std::string script = command + " \"$1\"";
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid < 0)
        throw core::InputError(fmt::format("external renderer: cannot start '{}'", command));
    if (pid == 0) {
        setpgid(0, 0);
        if (chdir(folder.c_str()) != 0) _exit(126);
        const int out = open("stdout.log", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err = open("stderr.log", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (out >= 0) dup2(out, STDOUT_FILENO);
        if (err >= 0) dup2(err, STDERR_FILENO);
        signal(SIGINT, SIG_DFL);
        signal(SIGTERM, SIG_DFL);
        execl("/bin/sh", "sh", "-c", script.c_str(), "sh", request.c_str(), nullptr);
        _exit(127);
    }
    setpgid(pid, pid);
    CommandRun run;
    int status = 0;
    for (;;) {
        const pid_t done = waitpid(pid, &status, WNOHANG);
        if (done == pid) break;
        run.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const bool cancelled = cancel && cancel->load();
        if (run.seconds > timeoutSeconds || cancelled) {
            kill(-pid, SIGKILL);
            waitpid(pid, &status, 0);
            run.timedOut = !cancelled;
            core::throwIfCancelled(cancel);
            return run;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    kill(-pid, SIGKILL);  // whatever it left running in its group
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return run;
}

}  // namespace

ExternalRenderer::ExternalRenderer(ExternalSettings settings, const LoadedScene& scene)
    : mSettings(std::move(settings)), mScene(scene) {
    if (mSettings.command.empty())
        throw core::InputError("external renderer: no command (--external-command CMD)");
    if (!(mSettings.timeoutSeconds > 0.0))
        throw core::InputError(fmt::format(
            "external renderer: the time limit must be > 0 s, got {}", mSettings.timeoutSeconds));
}

core::Frame ExternalRenderer::render(const core::RenderInput& in) {
    core::throwIfCancelled(in.cancel);
    core::requireWholeFrame(in, "external");
    const std::int64_t frameNumber = in.scene.frame;
    const fs::path folder = mSettings.root / in.scene.name / "external" / frameFolder(frameNumber);
    auto fail = [&](const std::string& what) {
        return core::InputError(fmt::format("external renderer '{}', frame {} of {}: {}",
                                            mSettings.command, frameNumber, in.scene.name, what));
    };
    fs::remove_all(folder);
    fs::create_directories(folder / "out");
    // The frame exported as `export` writes it (its textures, its particles, its camera).
    LoadedScene s{in.scene, mScene.raymarch, mScene.realtime, in.materials, in.particles};
    json scene = sceneExportJson(s, folder);
    const json entry = exportFrame(s, frameNumber, folder);
    scene["frames"] = json::array({entry});
    scene["camera"] = entry["camera"];
    core::writeTextFile(folder / "scene.json", scene.dump(2) + "\n");
    const json request = {
        {"format", REQUEST_FORMAT},
        {"version", REQUEST_VERSION},
        {"scene", "scene.json"},
        {"frame", frameNumber},
        {"particles", entry["particles"]},
        {"camera", entry["camera"]},
        {"width", in.scene.camera.width},
        {"height", in.scene.camera.height},
        {"time_limit_s", mSettings.timeoutSeconds},
        {"output", {{"image", "out/image.exr"}, {"timings", "out/timings.json"}}}};
    core::writeTextFile(folder / "request.json", request.dump(2) + "\n");

    // The request's path as the command sees it, from its working folder (whatever --out was).
    const CommandRun run =
        runCommand(mSettings.command, "request.json", folder, mSettings.timeoutSeconds, in.cancel);
    if (run.timedOut)
        throw fail(fmt::format("passed its time limit of {} s; its process group was ended",
                               mSettings.timeoutSeconds));
    if (run.exitCode == 127 || run.exitCode == 126)
        throw fail(fmt::format("the command was not found or is not executable (exit {}):{}",
                               run.exitCode, lastLines(folder / "stderr.log", 5)));
    if (run.exitCode != 0)
        throw fail(fmt::format("exited with {}; the last lines of its standard error:{}",
                               run.exitCode, lastLines(folder / "stderr.log", 10)));
    const fs::path imageFile = folder / "out" / "image.exr";
    if (!fs::exists(imageFile))
        throw fail(
            fmt::format("wrote no image at {} (the request's output.image)", imageFile.string()));
    core::Frame frame;
    frame.timingsMs["command"] = run.seconds * 1e3;
    frame.timingsMs["total"] = run.seconds * 1e3;
    try {
        frame.image = readTestImage(imageFile, in.scene.camera.width, in.scene.camera.height);
        for (const auto& [stage, ms] : readTestTimings(folder / "out" / "timings.json"))
            frame.timingsMs[stage] = ms;
    } catch (const core::InputError& e) {
        throw fail(e.what());
    }
    frame.display =
        core::tonemappedBeauty(frame.image, static_cast<float>(in.scene.camera.exposure));
    frame.renderer = "external";
    frame.device = "external: " + mSettings.command;
    frame.particleCount = in.particles.particles.size();
    frame.settings = {{"external.command", mSettings.command},
                      {"external.time_limit_s", mSettings.timeoutSeconds}};
    return frame;
}

}  // namespace twinrender::app
