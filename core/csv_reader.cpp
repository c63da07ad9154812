// CSV: a header row naming the columns, then one particle per row. Lines whose first
// non-blank character is '#' and blank lines are skipped anywhere. Columns not listed in
// FIELD_NAMES are ignored (velocities and the like are common).
#include "core/csv_reader.h"

#include <fmt/format.h>

#include <array>
#include <cctype>
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

std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return s;
}

std::vector<std::string_view> splitCommas(std::string_view line) {
    std::vector<std::string_view> fields;
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = line.find(',', start);
        fields.push_back(trim(line.substr(start, comma - start)));
        if (comma == std::string_view::npos) return fields;
        start = comma + 1;
    }
}

}  // namespace

ParticleFileData readCsv(const fs::path& path) {
    const std::string text = readWholeFile(path);
    if (text.empty()) throw InputError(fmt::format("{}: the file is empty", path.string()));
    std::string_view rest(text);
    if (rest.starts_with("\xEF\xBB\xBF")) rest.remove_prefix(3);  // UTF-8 byte order mark

    std::vector<std::optional<Field>> columns;  // per CSV column: the field it fills
    std::vector<std::string> columnNames;
    int headerLine = 0;
    std::optional<FieldSink> sink;
    std::vector<int> lineOf;  // per particle, for validation messages
    int line = 0;
    while (!rest.empty()) {
        const std::size_t eol = rest.find('\n');
        std::string_view row = rest.substr(0, eol);
        rest.remove_prefix(eol == std::string_view::npos ? rest.size() : eol + 1);
        ++line;
        const std::string_view content = trim(row);
        if (content.empty() || content.front() == '#') continue;
        const std::vector<std::string_view> cells = splitCommas(content);

        if (!sink) {
            headerLine = line;
            std::array<bool, FIELD_COUNT> present{};
            for (std::size_t c = 0; c < cells.size(); ++c) {
                std::string_view name = cells[c];
                if (name.size() >= 2 && name.front() == '"' && name.back() == '"')
                    name = trim(name.substr(1, name.size() - 2));
                if (name.empty())
                    throw InputError(
                        fmt::format("{}:{}: header column {} has no name; name every column",
                                    path.string(), line, c + 1));
                const std::optional<Field> f = fieldByName(name);
                if (f) {
                    if (present[static_cast<std::size_t>(*f)])
                        throw InputError(
                            fmt::format("{}:{}: column '{}' appears twice in the header; keep one",
                                        path.string(), line, name));
                    present[static_cast<std::size_t>(*f)] = true;
                }
                columns.push_back(f);
                columnNames.emplace_back(name);
            }
            for (Field f : {Field::X, Field::Y, Field::Z, Field::H})
                if (!present[static_cast<std::size_t>(f)])
                    throw InputError(
                        fmt::format("{}:{}: the header has no column '{}'; CSV "
                                    "particle files need columns {}",
                                    path.string(), line, FIELD_NAMES[static_cast<std::size_t>(f)],
                                    COLUMNS_HINT));
            if (present[static_cast<std::size_t>(Field::U)] !=
                present[static_cast<std::size_t>(Field::V)])
                throw InputError(
                    fmt::format("{}:{}: the header has only one of the texture "
                                "coordinate columns 'u' and 'v'; give both or neither",
                                path.string(), line));
            sink.emplace(present);
            continue;
        }

        if (cells.size() != columns.size())
            throw InputError(
                fmt::format("{}:{}: expected {} columns (as the header on line {}), "
                            "found {}; give every row one value per column",
                            path.string(), line, columns.size(), headerLine, cells.size()));
        std::array<double, FIELD_COUNT> values{};
        for (std::size_t c = 0; c < cells.size(); ++c) {
            if (!columns[c]) continue;
            const std::optional<double> v = parseNumber(cells[c]);
            if (!v)
                throw InputError(
                    fmt::format("{}:{}: column '{}' (column {}): cannot parse '{}' "
                                "as a number; write a decimal number",
                                path.string(), line, columnNames[c], c + 1, cells[c]));
            values[static_cast<std::size_t>(*columns[c])] = *v;
        }
        const std::size_t index = lineOf.size();
        sink->add(values,
                  [&] { return fmt::format("{}:{}: particle {}", path.string(), line, index); });
        lineOf.push_back(line);
    }
    if (!sink)
        throw InputError(
            fmt::format("{}: the file has no header row (only comments or blank "
                        "lines); start with a header naming the columns {}",
                        path.string(), COLUMNS_HINT));
    ParticleFileData data = sink->take();
    validateParticles(data, path, [&](std::size_t i) {
        return fmt::format("{}:{}: particle {}", path.string(), lineOf[i], i);
    });
    return data;
}

}  // namespace twinrender::core::particle_io
