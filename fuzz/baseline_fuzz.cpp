// Fuzz target baseline: a baseline file (--baseline), parsed and compared with a run's metrics.
#include <cstddef>
#include <cstdint>

#include "compare/baseline.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace twinrender;
    const auto file = fuzz::writeScratchFile("baseline.json", fuzz::asText(data, size));
    fuzz::expectCleanOutcome([&] {
        const compare::Baseline baseline = compare::readBaseline(file);
        const compare::MetricValues metrics = {{"beauty.flip", 0.05}, {"beauty.psnr", 31.0}};
        for (const auto& [scene, blessed] : baseline.scenes)
            compare::compareToBaseline(scene, metrics, baseline, &blessed.settings);
        compare::toJson(baseline);
    });
    return 0;
}
