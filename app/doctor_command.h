// `twinrender doctor`: what a user runs first on a new machine. Prints the GL device and the
// limits the real-time renderer needs, compiles every program variant it can build
// (realtime/program_variants.h) and prints every compile error, runs the per-set self-check
// (realtime/self_check.h) on a small scene, and ends with a verdict: exit 0 when all pass, 2
// when a program does not compile, a limit is short or the self-check fails, 4 without GL.
#pragma once

#include <string>
#include <vector>

#include "app/exit_code.h"
#include "app/render_job.h"

namespace twinrender::app {

struct DoctorOptions {
    std::string scene = "scenes/planet.toml";  // the self-check's scene
    std::vector<std::string> sets;             // --set overrides of it
    bool requireGpu = false;
};
ExitCode runDoctor(const DoctorOptions& options);

// The doctor's self-check on a scene (its own settings): prints the table, returns Pass or Fail.
ExitCode selfCheckScene(const LoadedScene& scene, Devices& devices);

}  // namespace twinrender::app
