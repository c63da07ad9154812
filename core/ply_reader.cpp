// PLY (http://paulbourke.net/dataformats/ply/): ascii, binary_little_endian and (as it costs
// nothing more) binary_big_endian. Elements other than "vertex" and unknown properties are
// skipped, list properties included.
#include "core/ply_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/particle_columns.h"
#include "core/particle_file_reading.h"

namespace twinrender::core::particle_io {
namespace fs = std::filesystem;

namespace {

enum class PlyType { INT8, UINT8, INT16, UINT16, INT32, UINT32, FLOAT32, FLOAT64 };

std::optional<PlyType> plyTypeByName(std::string_view name) {
    static constexpr std::array<std::pair<std::string_view, PlyType>, 16> TYPES = {{
        {"char", PlyType::INT8},
        {"int8", PlyType::INT8},
        {"uchar", PlyType::UINT8},
        {"uint8", PlyType::UINT8},
        {"short", PlyType::INT16},
        {"int16", PlyType::INT16},
        {"ushort", PlyType::UINT16},
        {"uint16", PlyType::UINT16},
        {"int", PlyType::INT32},
        {"int32", PlyType::INT32},
        {"uint", PlyType::UINT32},
        {"uint32", PlyType::UINT32},
        {"float", PlyType::FLOAT32},
        {"float32", PlyType::FLOAT32},
        {"double", PlyType::FLOAT64},
        {"float64", PlyType::FLOAT64},
    }};
    for (const auto& [n, t] : TYPES)
        if (n == name) return t;
    return std::nullopt;
}

std::size_t plyTypeSize(PlyType t) {
    switch (t) {
        case PlyType::INT8:
        case PlyType::UINT8:
            return 1;
        case PlyType::INT16:
        case PlyType::UINT16:
            return 2;
        case PlyType::INT32:
        case PlyType::UINT32:
        case PlyType::FLOAT32:
            return 4;
        case PlyType::FLOAT64:
            return 8;
    }
    return 0;
}

double plyLoad(PlyType t, const unsigned char* p, bool bigEndian) {
    switch (t) {
        case PlyType::INT8:
            return loadBytes<std::int8_t>(p, bigEndian);
        case PlyType::UINT8:
            return loadBytes<std::uint8_t>(p, bigEndian);
        case PlyType::INT16:
            return loadBytes<std::int16_t>(p, bigEndian);
        case PlyType::UINT16:
            return loadBytes<std::uint16_t>(p, bigEndian);
        case PlyType::INT32:
            return loadBytes<std::int32_t>(p, bigEndian);
        case PlyType::UINT32:
            return loadBytes<std::uint32_t>(p, bigEndian);
        case PlyType::FLOAT32:
            return loadBytes<float>(p, bigEndian);
        case PlyType::FLOAT64:
            return loadBytes<double>(p, bigEndian);
    }
    return 0.0;
}

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::FLOAT32;  // of the values (of a list's items)
    bool isList = false;
    PlyType countType = PlyType::UINT8;  // of a list's item count
    std::optional<Field> field;          // set for vertex properties we read
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;
    int headerLine = 0;
};

enum class PlyFormat { ASCII, BINARY_LITTLE_ENDIAN, BINARY_BIG_ENDIAN };

class PlyReader {
  public:
    explicit PlyReader(const fs::path& path) : mPath(path), mBytes(readWholeFile(path)) {}

    ParticleFileData read() {
        if (mBytes.empty()) throw InputError(fmt::format("{}: the file is empty", mPath.string()));
        parseHeader();
        const PlyElement& vertex = findVertex();
        std::array<bool, FIELD_COUNT> present{};
        for (const PlyProperty& p : vertex.properties)
            if (p.field) present[static_cast<std::size_t>(*p.field)] = true;
        mSink.emplace(present);
        if (mFormat == PlyFormat::ASCII)
            readAscii();
        else
            readBinary(mFormat == PlyFormat::BINARY_BIG_ENDIAN);
        ParticleFileData data = mSink->take();
        validateParticles(data, mPath, [&](std::size_t i) {
            return fmt::format("{}: vertex {}", mPath.string(), i);
        });
        return data;
    }

  private:
    [[noreturn]] void headerError(int line, const std::string& what) const {
        throw InputError(fmt::format("{}: header line {}: {}", mPath.string(), line, what));
    }

    void parseHeader() {
        std::size_t pos = 0;
        int line = 0;
        bool sawFormat = false;
        for (;;) {
            if (pos >= mBytes.size())
                throw InputError(
                    fmt::format("{}: the PLY header has no end_header line; the file "
                                "is truncated or not a PLY file",
                                mPath.string()));
            std::size_t eol = mBytes.find('\n', pos);
            const std::size_t next = eol == std::string::npos ? mBytes.size() : eol + 1;
            if (eol == std::string::npos) eol = mBytes.size();
            std::string_view text(mBytes.data() + pos, eol - pos);
            if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
            pos = next;
            ++line;
            std::vector<std::string_view> words = splitWords(text);
            if (line == 1) {
                if (words.size() != 1 || words[0] != "ply")
                    throw InputError(
                        fmt::format("{}: not a PLY file (the first line is not "
                                    "\"ply\"); give a PLY, .ssf or .csv file",
                                    mPath.string()));
                continue;
            }
            if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
            if (words[0] == "end_header") {
                if (!sawFormat) headerError(line, "end_header before any format line");
                mDataStart = pos;
                mDataLine = line + 1;
                return;
            }
            if (words[0] == "format") {
                if (words.size() != 3) headerError(line, "expected \"format <type> 1.0\"");
                if (words[1] == "ascii")
                    mFormat = PlyFormat::ASCII;
                else if (words[1] == "binary_little_endian")
                    mFormat = PlyFormat::BINARY_LITTLE_ENDIAN;
                else if (words[1] == "binary_big_endian")
                    mFormat = PlyFormat::BINARY_BIG_ENDIAN;
                else
                    headerError(line, fmt::format("unknown format '{}'; use ascii or "
                                                  "binary_little_endian",
                                                  words[1]));
                sawFormat = true;
            } else if (words[0] == "element") {
                std::uint64_t count = 0;
                if (words.size() != 3 || !parseCount(words[2], count))
                    headerError(line, "expected \"element <name> <count>\"");
                mElements.push_back({std::string(words[1]), count, {}, line});
            } else if (words[0] == "property") {
                if (mElements.empty()) headerError(line, "property before any element");
                mElements.back().properties.push_back(parseProperty(words, line));
            } else {
                headerError(line, fmt::format("unknown keyword '{}'; expected format, element, "
                                              "property, comment or end_header",
                                              words[0]));
            }
        }
    }

    PlyProperty parseProperty(const std::vector<std::string_view>& words, int line) const {
        PlyProperty p;
        const bool vertex = mElements.back().name == "vertex";
        if (words.size() == 5 && words[1] == "list") {
            const auto countType = plyTypeByName(words[2]);
            const auto type = plyTypeByName(words[3]);
            if (!countType || !type)
                headerError(line, fmt::format("unknown type in list property '{}'", words[4]));
            if (*countType == PlyType::FLOAT32 || *countType == PlyType::FLOAT64)
                headerError(line, fmt::format("list property '{}' has a floating-point count type",
                                              words[4]));
            p = {std::string(words[4]), *type, true, *countType, std::nullopt};
            if (vertex && fieldByName(p.name))
                headerError(line, fmt::format("vertex property '{}' is a list; it must be a "
                                              "single value",
                                              p.name));
            return p;
        }
        if (words.size() != 3)
            headerError(line,
                        "expected \"property <type> <name>\" or \"property list "
                        "<count type> <type> <name>\"");
        const auto type = plyTypeByName(words[1]);
        if (!type)
            headerError(line, fmt::format("unknown type '{}' of property '{}'; use char, uchar, "
                                          "short, ushort, int, uint, float or double",
                                          words[1], words[2]));
        p.name = std::string(words[2]);
        p.type = *type;
        if (vertex) {
            p.field = fieldByName(p.name);
            if (p.field)
                for (const PlyProperty& other : mElements.back().properties)
                    if (other.name == p.name)
                        headerError(line,
                                    fmt::format("vertex property '{}' appears twice", p.name));
        }
        return p;
    }

    const PlyElement& findVertex() const {
        const PlyElement* vertex = nullptr;
        for (const PlyElement& e : mElements)
            if (e.name == "vertex") {
                if (vertex) headerError(e.headerLine, "a second 'element vertex'");
                vertex = &e;
            }
        if (!vertex)
            throw InputError(
                fmt::format("{}: the PLY header has no 'element vertex'; particles "
                            "are vertices with properties {}",
                            mPath.string(), COLUMNS_HINT));
        std::array<bool, FIELD_COUNT> present{};
        for (const PlyProperty& p : vertex->properties)
            if (p.field) present[static_cast<std::size_t>(*p.field)] = true;
        for (Field f : {Field::X, Field::Y, Field::Z, Field::H})
            if (!present[static_cast<std::size_t>(f)])
                headerError(vertex->headerLine,
                            fmt::format("element vertex has no property '{}'; particles need "
                                        "properties {}",
                                        FIELD_NAMES[static_cast<std::size_t>(f)], COLUMNS_HINT));
        if (present[static_cast<std::size_t>(Field::U)] !=
            present[static_cast<std::size_t>(Field::V)])
            headerError(vertex->headerLine,
                        "element vertex has only one of the texture "
                        "coordinates 'u' and 'v'; give both or neither");
        if (vertex->count == 0)
            throw InputError(
                fmt::format("{}: the file holds no particles (element vertex 0); "
                            "write at least one vertex",
                            mPath.string()));
        return *vertex;
    }

    static std::vector<std::string_view> splitWords(std::string_view text) {
        std::vector<std::string_view> words;
        std::size_t i = 0;
        while (i < text.size()) {
            while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
            const std::size_t start = i;
            while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
            if (i > start) words.push_back(text.substr(start, i - start));
        }
        return words;
    }

    static bool parseCount(std::string_view text, std::uint64_t& count) {
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), count);
        return ec == std::errc() && end == text.data() + text.size();
    }

    // "vertex 12" or "'face' element 3", for messages.
    static std::string itemName(const PlyElement& e, std::uint64_t i) {
        return e.name == "vertex" ? fmt::format("vertex {}", i)
                                  : fmt::format("'{}' element {}", e.name, i);
    }

    // Ascii: whitespace-separated tokens; an item need not sit on one line.
    void readAscii() {
        std::size_t pos = mDataStart;
        int line = mDataLine;
        auto nextToken = [&](std::string_view& token) {
            while (pos < mBytes.size() && std::isspace(static_cast<unsigned char>(mBytes[pos]))) {
                if (mBytes[pos] == '\n') ++line;
                ++pos;
            }
            const std::size_t start = pos;
            while (pos < mBytes.size() && !std::isspace(static_cast<unsigned char>(mBytes[pos])))
                ++pos;
            token = std::string_view(mBytes.data() + start, pos - start);
            return !token.empty();
        };
        for (const PlyElement& e : mElements) {
            for (std::uint64_t i = 0; i < e.count; ++i) {
                std::array<double, FIELD_COUNT> values{};
                for (const PlyProperty& p : e.properties) {
                    std::string_view token;
                    auto need = [&] {
                        if (!nextToken(token))
                            throw InputError(fmt::format(
                                "{}: truncated: expected {} '{}' elements, the data ends in "
                                "{} (line {}); the file is incomplete: write it again",
                                mPath.string(), e.count, e.name, itemName(e, i), line));
                    };
                    need();
                    if (p.isList) {
                        const auto n = parseNumber(token);
                        if (!n || *n < 0 || *n != std::floor(*n))
                            throw InputError(
                                fmt::format("{}: {} (line {}): list property '{}' "
                                            "has count '{}'; expected a non-negative integer",
                                            mPath.string(), itemName(e, i), line, p.name, token));
                        for (double k = 0; k < *n; ++k) need();
                        continue;
                    }
                    if (!p.field) continue;
                    const auto v = parseNumber(token);
                    if (!v)
                        throw InputError(
                            fmt::format("{}: {} (line {}): property '{}': cannot "
                                        "parse '{}' as a number; write a decimal number",
                                        mPath.string(), itemName(e, i), line, p.name, token));
                    values[static_cast<std::size_t>(*p.field)] = *v;
                }
                if (e.name == "vertex")
                    mSink->add(values, [&] {
                        return fmt::format("{}: vertex {} (line {})", mPath.string(), i, line);
                    });
            }
        }
    }

    void readBinary(bool bigEndian) {
        const auto* bytes = reinterpret_cast<const unsigned char*>(mBytes.data());
        std::uint64_t pos = mDataStart;
        const std::uint64_t size = mBytes.size();
        auto require = [&](std::uint64_t n, const PlyElement& e, std::uint64_t i) {
            if (n > size || pos > size - n)
                throw InputError(
                    fmt::format("{}: truncated: expected {} '{}' elements, the data "
                                "ends in {} at byte {}, file has {} bytes; the file "
                                "is incomplete: write it again",
                                mPath.string(), e.count, e.name, itemName(e, i), pos, size));
        };
        for (const PlyElement& e : mElements) {
            const bool isVertex = e.name == "vertex";
            const bool fixedSize = std::none_of(e.properties.begin(), e.properties.end(),
                                                [](const PlyProperty& p) { return p.isList; });
            if (!isVertex && fixedSize) {
                // Whole element at once; per item only to name the truncated one.
                std::uint64_t stride = 0;
                for (const PlyProperty& p : e.properties) stride += plyTypeSize(p.type);
                if (stride > 0 && e.count > (size - pos) / stride) {
                    const std::uint64_t complete = (size - pos) / stride;
                    pos += stride * complete;
                    require(stride, e, complete);
                }
                pos += stride * e.count;
                continue;
            }
            for (std::uint64_t i = 0; i < e.count; ++i) {
                std::array<double, FIELD_COUNT> values{};
                for (const PlyProperty& p : e.properties) {
                    if (p.isList) {
                        require(plyTypeSize(p.countType), e, i);
                        const double n = plyLoad(p.countType, bytes + pos, bigEndian);
                        pos += plyTypeSize(p.countType);
                        if (n < 0)
                            throw InputError(
                                fmt::format("{}: {}: list property '{}' has a "
                                            "negative count {}; the file is corrupt",
                                            mPath.string(), itemName(e, i), p.name, n));
                        const std::uint64_t listBytes =
                            static_cast<std::uint64_t>(n) * plyTypeSize(p.type);
                        require(listBytes, e, i);
                        pos += listBytes;
                        continue;
                    }
                    const std::size_t valueSize = plyTypeSize(p.type);
                    require(valueSize, e, i);
                    if (p.field)
                        values[static_cast<std::size_t>(*p.field)] =
                            plyLoad(p.type, bytes + pos, bigEndian);
                    pos += valueSize;
                }
                if (isVertex)
                    mSink->add(values,
                               [&] { return fmt::format("{}: vertex {}", mPath.string(), i); });
            }
        }
    }

    fs::path mPath;
    std::string mBytes;
    PlyFormat mFormat = PlyFormat::ASCII;
    std::vector<PlyElement> mElements;
    std::size_t mDataStart = 0;  // byte offset of the first element's data
    int mDataLine = 0;           // line of mDataStart (ascii messages)
    std::optional<FieldSink> mSink;
};

}  // namespace

ParticleFileData readPly(const fs::path& path) {
    return PlyReader(path).read();
}

}  // namespace twinrender::core::particle_io
