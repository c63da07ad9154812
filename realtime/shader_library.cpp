#include "realtime/shader_library.h"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>

#include "realtime/gl/error.h"

namespace twinrender::realtime {

namespace {

struct Composer {
    gl::ShaderSource out;

    int fileNumber(std::string_view name) {
        auto it = std::find(out.files.begin(), out.files.end(), name);
        if (it != out.files.end()) return -1;  // already included
        out.files.emplace_back(name);
        return static_cast<int>(out.files.size()) - 1;
    }

    void append(std::string_view name, int number) {
        std::istringstream lines{std::string(shaderFile(name))};
        out.text += fmt::format("#line 1 {}\n", number);
        std::string line;
        int lineNumber = 0;
        while (std::getline(lines, line)) {
            ++lineNumber;
            const auto first = line.find_first_not_of(" \t");
            if (first != std::string::npos && line.compare(first, 8, "#include") == 0) {
                const auto open = line.find('"'), close = line.rfind('"');
                if (open == std::string::npos || close <= open)
                    throw gl::Error(fmt::format("{}:{}: malformed #include", name, lineNumber));
                const std::string included = line.substr(open + 1, close - open - 1);
                const int n = fileNumber(included);
                if (n >= 0) append(included, n);
                out.text += fmt::format("#line {} {}\n", lineNumber + 1, number);
                continue;
            }
            out.text += line;
            out.text += '\n';
        }
    }
};

}  // namespace

std::string_view shaderFile(std::string_view name) {
    if (const auto text = core::findEmbeddedFile(embeddedShaderFiles(), name)) return *text;
    throw gl::Error(fmt::format("no embedded shader file '{}' (realtime/shaders/)", name));
}

gl::ShaderSource composeShader(std::string_view file, std::span<const std::string> defines) {
    Composer c;
    c.out.text = "#version 450 core\n";
    for (const auto& d : defines) c.out.text += "#define " + d + "\n";
    c.out.files.emplace_back("(version and defines)");
    c.append(file, c.fileNumber(file));
    return std::move(c.out);
}

const gl::Program& ProgramCache::get(std::string_view vertexFile, std::string_view fragmentFile,
                                     const std::vector<std::string>& defines) {
    std::string key = fmt::format("{}+{}", vertexFile, fragmentFile);
    for (const auto& d : defines) key += " -D" + d;
    auto it = mPrograms.find(key);
    if (it == mPrograms.end()) {
        gl::Program program(key, composeShader(vertexFile, defines),
                            composeShader(fragmentFile, defines));
        it = mPrograms.emplace(key, std::move(program)).first;
    }
    return it->second;
}

}  // namespace twinrender::realtime
