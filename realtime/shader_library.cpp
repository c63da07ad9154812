#include "realtime/shader_library.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <sstream>

#include "realtime/gl/conversions.h"
#include "realtime/gl/error.h"

namespace twinrender::realtime {

namespace {

struct Composer {
    gl::ShaderSource out;
    const IncludedFile* user = nullptr;
    std::vector<std::string> included;  // by #include name, parallel to out.files
    int line = 1;                       // the next line of out.text

    int fileNumber(std::string_view name) {
        auto it = std::find(included.begin(), included.end(), name);
        if (it != included.end()) return -1;  // already included
        included.emplace_back(name);
        out.files.emplace_back(user && name == user->include ? user->shownName : name);
        return static_cast<int>(out.files.size()) - 1;
    }

    std::string_view text(std::string_view name) const {
        return user && name == user->include ? std::string_view(user->text) : shaderFile(name);
    }

    void addLine(std::string_view text) {
        out.text += text;
        out.text += '\n';
        ++line;
    }

    void append(std::string_view name, int number) {
        std::istringstream lines{std::string(text(name))};
        out.spans.push_back({line, number, 1});
        std::string text;
        int lineNumber = 0;
        while (std::getline(lines, text)) {
            ++lineNumber;
            const auto first = text.find_first_not_of(" \t");
            if (first != std::string::npos && text.compare(first, 8, "#include") == 0) {
                const auto open = text.find('"'), close = text.rfind('"');
                if (open == std::string::npos || close <= open)
                    throw gl::Error(fmt::format("{}:{}: malformed #include", name, lineNumber));
                const std::string included = text.substr(open + 1, close - open - 1);
                const int n = fileNumber(included);
                if (n >= 0) append(included, n);
                out.spans.push_back({line, number, lineNumber + 1});
                continue;
            }
            addLine(text);
        }
    }
};

// `defines` after the conversion test mode's (gl/conversions.h), which every program of the
// process is compiled with and no program's name shows.
std::vector<std::string> withConversionDefines(const std::vector<std::string>& defines) {
    std::vector<std::string> all = gl::conversionDefines();
    all.insert(all.end(), defines.begin(), defines.end());
    return all;
}

}  // namespace

std::string_view shaderFile(std::string_view name) {
    if (const auto text = core::findEmbeddedFile(embeddedShaderFiles(), name)) return *text;
    throw gl::Error(fmt::format("no embedded shader file '{}' (realtime/shaders/)", name));
}

gl::ShaderSource composeShader(std::string_view file, std::span<const std::string> defines,
                               const IncludedFile* user) {
    Composer c;
    c.user = user;
    c.out.spans.push_back({1, c.fileNumber("(version and defines)"), 1});
    c.addLine("#version 450 core");
    for (const auto& d : defines) c.addLine("#define " + d);
    c.append(file, c.fileNumber(file));
    return std::move(c.out);
}

const gl::Program& ProgramCache::get(std::string_view vertexFile, std::string_view fragmentFile,
                                     const std::vector<std::string>& defines,
                                     const IncludedFile* user) {
    std::string key = drawName(vertexFile, fragmentFile, defines);
    if (user)
        key += fmt::format(" {}={} ({:016x})", user->include, user->shownName,
                           std::hash<std::string>{}(user->text));
    auto it = mPrograms.find(key);
    if (it == mPrograms.end()) {
        const std::vector<std::string> all = withConversionDefines(defines);
        gl::Program program(key, composeShader(vertexFile, all),
                            composeShader(fragmentFile, all, user));
        it = mPrograms.emplace(key, std::move(program)).first;
    }
    return it->second;
}

const gl::Program& ProgramCache::compute(std::string_view file,
                                         const std::vector<std::string>& defines) {
    const std::string key = computeName(file, defines);
    auto it = mPrograms.find(key);
    if (it == mPrograms.end())
        it =
            mPrograms
                .emplace(key, gl::Program(key, composeShader(file, withConversionDefines(defines))))
                .first;
    return it->second;
}

std::vector<std::string> ProgramCache::names() const {
    std::vector<std::string> out;
    for (const auto& [name, program] : mPrograms) out.push_back(name);
    return out;
}

std::string ProgramCache::drawName(std::string_view vertexFile, std::string_view fragmentFile,
                                   std::span<const std::string> defines) {
    std::string name = fmt::format("{}+{}", vertexFile, fragmentFile);
    for (const auto& d : defines) name += " -D" + d;
    return name;
}

std::string ProgramCache::computeName(std::string_view file, std::span<const std::string> defines) {
    std::string name(file);
    for (const auto& d : defines) name += " -D" + d;
    return name;
}

}  // namespace twinrender::realtime
