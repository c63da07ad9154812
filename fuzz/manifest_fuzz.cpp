// Fuzz target manifest: the shard manifests `merge` reads (DIR/shard.json), merged as
// `twinrender merge` does. Input: the manifests of the shards, separated by lines "%%".
// Whatever the manifests name, nothing may appear outside the output folder: beside the
// shards waits a folder that a scene named "../escaped" would lead to.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "app/merge_command.h"
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
    fs::create_directories(root / "escaped");
    fuzz::writeScratchFile("merge/escaped/secret.txt", "not a shard's");
    options.out = (root / "out").string();
    options.commandLine = "twinrender merge";
    // Every path under the scratch folder but the output folder's.
    const auto outside = [&] {
        std::set<std::string> paths;
        for (auto it = fs::recursive_directory_iterator(fuzz::scratchDir());
             it != fs::recursive_directory_iterator(); ++it) {
            if (it->path() == root / "out") {
                it.disable_recursion_pending();
                continue;
            }
            paths.insert(it->path().string());
        }
        return paths;
    };
    const std::set<std::string> before = outside();
    fuzz::expectCleanOutcome([&] { app::runMerge(options); });
    for (const std::string& p : outside())
        if (!before.count(p)) {
            std::fprintf(stderr, "merge wrote %s, outside its output folder\n", p.c_str());
            std::abort();
        }
    return 0;
}
