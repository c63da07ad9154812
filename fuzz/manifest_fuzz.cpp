// Fuzz target manifest: the shard manifests `merge` reads (DIR/shard.json), merged as
// `twinrender merge` does. Input: the manifests of the shards, separated by lines "%%".
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "app/shard.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace twinrender;
    namespace fs = std::filesystem;
    const std::vector<std::string> parts = fuzz::splitParts(fuzz::asText(data, size));
    app::MergeOptions options;
    const fs::path root = fuzz::scratchDir() / "merge";
    fs::remove_all(root);
    for (std::size_t i = 0; i < parts.size(); ++i) {
        const fs::path dir = root / ("shard" + std::to_string(i + 1));
        fs::create_directories(dir);
        fuzz::writeScratchFile(fs::relative(dir / "shard.json", fuzz::scratchDir()).string(),
                               parts[i]);
        options.inputs.push_back(dir.string());
    }
    options.out = (root / "out").string();
    options.commandLine = "twinrender merge";
    fuzz::expectCleanOutcome([&] { app::runMerge(options); });
    return 0;
}
