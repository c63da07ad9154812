// A file compiled into the binary at build time (cmake/embed_files.cmake): shaders, the
// report's stylesheet and scripts.
#pragma once

#include <optional>
#include <span>
#include <string_view>

namespace twinrender::core {

struct EmbeddedFile {
    std::string_view name;  // file name, e.g. "gbuffer.frag"
    std::string_view text;
};

// The text of the file called `name` among `files`, or nullopt.
inline std::optional<std::string_view> findEmbeddedFile(std::span<const EmbeddedFile> files,
                                                        std::string_view name) {
    for (const EmbeddedFile& f : files)
        if (f.name == name) return f.text;
    return std::nullopt;
}

}  // namespace twinrender::core
