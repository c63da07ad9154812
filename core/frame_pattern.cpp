#include "core/frame_pattern.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <regex>
#include <system_error>

#include "core/error.h"

namespace twinrender::core {

namespace fs = std::filesystem;

namespace {

// The glob as a regular expression over a file name: each wildcard a capture group.
std::regex globRegex(const std::string& glob) {
    std::string re;
    for (char c : glob) {
        if (c == '*')
            re += "(.*)";
        else if (c == '?')
            re += "(.)";
        else if (std::ispunct(static_cast<unsigned char>(c)) && c != '_')
            re += std::string("\\") + c;  // ASCII punctuation: taken literally
        else
            re += c;  // letters, digits, spaces and the bytes of UTF-8 characters
    }
    return std::regex(re);
}

// The value of the last run of digits in `text`; nullopt when it has none or it does not fit.
std::optional<std::int64_t> lastNumber(const std::string& text) {
    auto end = text.find_last_of("0123456789");
    if (end == std::string::npos) return std::nullopt;
    auto begin = end;
    while (begin > 0 && std::isdigit(static_cast<unsigned char>(text[begin - 1]))) --begin;
    const std::string digits = text.substr(begin, end - begin + 1);
    if (digits.size() > 18) return std::nullopt;
    return std::stoll(digits);
}

}  // namespace

std::optional<FramePattern> FramePattern::parse(const fs::path& path, const std::string& where) {
    const std::string name = path.filename().string();
    FramePattern p;
    p.mPath = path;
    p.mWhere = where;
    p.mGlob = name.find_first_of("*?") != std::string::npos;
    bool conversion = false;
    std::string literal;  // the name with %% unescaped, up to the conversion
    for (std::size_t i = 0; i < name.size(); ++i) {
        if (name[i] != '%') {
            literal += name[i];
            continue;
        }
        if (i + 1 < name.size() && name[i + 1] == '%') {
            literal += '%';
            ++i;
            continue;
        }
        std::size_t j = i + 1;
        const bool zero = j < name.size() && name[j] == '0';
        std::string width;
        while (j < name.size() && std::isdigit(static_cast<unsigned char>(name[j])))
            width += name[j++];
        if (j >= name.size() || name[j] != 'd')
            throw InputError(
                fmt::format("{}: '{}' has a printf conversion other than %d or %0Nd (write %% for "
                            "a literal %)",
                            where, name));
        if (conversion)
            throw InputError(fmt::format(
                "{}: '{}' has two frame-number conversions; a sequence has one", where, name));
        conversion = true;
        p.mPrefix = literal;
        literal.clear();
        p.mZeroPad = zero;
        p.mWidth = width.empty() ? 0 : std::min(std::stoi(width), 18);
        i = j;
    }
    if (conversion && p.mGlob)
        throw InputError(fmt::format(
            "{}: '{}' mixes a printf conversion with glob wildcards; use one or the other", where,
            name));
    if (!conversion && !p.mGlob) return std::nullopt;
    if (conversion) p.mSuffix = literal;
    return p;
}

std::vector<FrameFile> FramePattern::list() const {
    const fs::path dir = mPath.parent_path();
    const std::string name = mPath.filename().string();
    std::error_code ec;
    fs::directory_iterator it(dir, ec);
    if (ec)
        throw InputError(
            fmt::format("{}: the folder {} of the sequence {} cannot be listed ({}); "
                        "paths are relative to the scene file",
                        mWhere, dir.string(), name, ec.message()));
    const std::regex glob = mGlob ? globRegex(name) : std::regex();
    std::map<std::int64_t, fs::path> found;
    for (const auto& entry : it) {
        const std::string file = entry.path().filename().string();
        std::optional<std::int64_t> number;
        if (mGlob) {
            std::smatch m;
            if (!std::regex_match(file, m, glob)) continue;
            std::string matched;
            for (std::size_t k = 1; k < m.size(); ++k) matched += m[k].str() + " ";
            number = lastNumber(matched);
            if (!number)
                throw InputError(fmt::format(
                    "{}: {} matches the sequence {} but its wildcards match no frame number; "
                    "rename it or narrow the pattern",
                    mWhere, entry.path().string(), name));
        } else {
            if (file.size() <= mPrefix.size() + mSuffix.size() || !file.starts_with(mPrefix) ||
                !file.ends_with(mSuffix))
                continue;
            const std::string digits =
                file.substr(mPrefix.size(), file.size() - mPrefix.size() - mSuffix.size());
            if (digits.size() > 18 || !std::all_of(digits.begin(), digits.end(), [](char c) {
                    return std::isdigit(static_cast<unsigned char>(c));
                }))
                continue;
            const std::int64_t n = std::stoll(digits);
            // Only the names the pattern prints: out_%04d.ssf takes out_0007.ssf, not out_7.ssf.
            if (this->file(n, {}).filename().string() != file) continue;
            number = n;
        }
        const auto [at, inserted] = found.emplace(*number, entry.path());
        if (!inserted)
            throw InputError(
                fmt::format("{}: {} and {} are both frame {} of the sequence {}; remove one",
                            mWhere, std::min(at->second, entry.path()).string(),
                            std::max(at->second, entry.path()).string(), *number, name));
    }
    std::vector<FrameFile> out;
    for (auto& [n, p] : found) out.push_back({n, p.lexically_normal()});
    return out;
}

fs::path FramePattern::file(std::int64_t number, const std::vector<FrameFile>& listed) const {
    if (mGlob) {
        const auto it =
            std::lower_bound(listed.begin(), listed.end(), number,
                             [](const FrameFile& f, std::int64_t n) { return f.number < n; });
        return it != listed.end() && it->number == number ? it->path : fs::path();
    }
    const std::string digits =
        mZeroPad ? fmt::format("{:0{}d}", number, mWidth) : fmt::format("{:{}d}", number, mWidth);
    return mPath.parent_path() / (mPrefix + digits + mSuffix);
}

}  // namespace twinrender::core
