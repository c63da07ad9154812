// Fuzz target thresholds: a thresholds file (--thresholds), parsed, resolved for a scene and
// evaluated against a set of metric values.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "compare/thresholds.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace twinrender;
    const auto file = fuzz::writeScratchFile("thresholds.toml", fuzz::asText(data, size));
    fuzz::expectCleanOutcome([&] {
        const compare::Thresholds thresholds = compare::Thresholds::parseFile(file);
        const compare::MetricValues metrics = {
            {"beauty.flip", 0.05}, {"beauty.psnr", 31.0}, {"depth.rmse", NAN}};
        compare::evaluate(metrics, thresholds.forScene("planet"));
        for (const auto& [scene, bounds] : thresholds.scenes())
            compare::evaluate(metrics, thresholds.forScene(scene));
    });
    return 0;
}
