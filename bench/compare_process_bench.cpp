// The whole `twinrender compare` process on a 1920x1080 PNG pair, as CI runs it: start-up,
// decoding both PNGs, every beauty metric, the ꟻLIP error map's PNG and metrics.json. Beside
// it, when TWINRENDER_NVLABS_FLIP names NVlabs' flip tool (github.com/NVlabs/flip, built as
// compare/testdata/reference_values.py builds it), that tool on the same pair in the same run
// (it computes ꟻLIP alone); and when TWINRENDER_COMPARE_BEFORE names another twinrender
// binary (a copy built from an earlier commit), that one too, for a before and after in one
// run. Run:
//   TWINRENDER_NVLABS_FLIP=/path/to/flip build/bench/compare_process_bench
//       --benchmark_repetitions=5 --benchmark_report_aggregates_only=true   (one line)
// and read the medians (wall time).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "bench/render_like_pair.h"
#include "core/image_io.h"
#include "core/install_layout.h"

namespace twinrender::compare {
namespace {

namespace fs = std::filesystem;

// The pair as 8-bit PNGs in a folder of its own, written once.
const fs::path& pairFolder() {
    static const fs::path dir = [] {
        const fs::path d =
            fs::temp_directory_path() / ("twinrender_compare_bench_" + std::to_string(getpid()));
        const Pair p;
        core::writeImage(p.reference, d / "ref.png");
        core::writeImage(p.test, d / "test.png");
        return d;
    }();
    return dir;
}

void runProcess(benchmark::State& state, const std::string& command) {
    for (auto _ : state)
        if (std::system((command + " > /dev/null 2>&1").c_str()) != 0)
            state.SkipWithError(("failed: " + command).c_str());
}

void runCompare(benchmark::State& state, const std::string& twinrender) {
    const fs::path& d = pairFolder();
    runProcess(state, twinrender + " compare " + (d / "ref.png").string() + " " +
                          (d / "test.png").string() + " --out " + (d / "out").string());
}

// The tool the variable names, or nullptr after marking the benchmark skipped.
const char* toolFrom(benchmark::State& state, const char* variable, const char* what) {
    const char* tool = std::getenv(variable);
    if (!tool) {
        state.SkipWithError(
            (std::string("set ") + variable + " to " + what + " to time it").c_str());
        for (auto _ : state) {
        }
    }
    return tool;
}

void BM_TwinrenderCompare(benchmark::State& state) {
    runCompare(state, (::twinrender::core::buildDir() / "app" / "twinrender").string());
}
BENCHMARK(BM_TwinrenderCompare)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

void BM_TwinrenderCompareBefore(benchmark::State& state) {
    if (const char* before = toolFrom(state, "TWINRENDER_COMPARE_BEFORE", "another twinrender"))
        runCompare(state, before);
}
BENCHMARK(BM_TwinrenderCompareBefore)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

void BM_NvlabsFlip(benchmark::State& state) {
    const char* tool = toolFrom(state, "TWINRENDER_NVLABS_FLIP", "NVlabs' flip tool");
    if (!tool) return;
    const fs::path& d = pairFolder();
    // -v 1: the mean only; the error map written as its PNG, as ours is.
    runProcess(state, std::string(tool) + " -r " + (d / "ref.png").string() + " -t " +
                          (d / "test.png").string() + " -v 1 -d " + (d / "nvlabs").string());
}
BENCHMARK(BM_NvlabsFlip)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace
}  // namespace twinrender::compare

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    std::error_code ec;
    std::filesystem::remove_all(twinrender::compare::pairFolder(), ec);
}
