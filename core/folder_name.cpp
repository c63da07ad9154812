#include "core/folder_name.h"

#include <fmt/format.h>

#include <array>

namespace twinrender::core {

namespace {

constexpr std::size_t kMaxBytes = 100;

bool isControl(unsigned char c) {
    return c < 0x20 || c == 0x7f;
}

// Whether `s` is well-formed UTF-8 (no overlong forms, no surrogates, at most U+10FFFF).
bool isUtf8(std::string_view s) {
    for (std::size_t i = 0; i < s.size();) {
        const auto c = static_cast<unsigned char>(s[i]);
        std::size_t n = 0;
        unsigned lo = 0x80, hi = 0xbf;  // the allowed range of the second byte
        if (c < 0x80) {
            ++i;
            continue;
        } else if (c >= 0xc2 && c <= 0xdf) {
            n = 1;
        } else if (c >= 0xe0 && c <= 0xef) {
            n = 2;
            if (c == 0xe0) lo = 0xa0;
            if (c == 0xed) hi = 0x9f;
        } else if (c >= 0xf0 && c <= 0xf4) {
            n = 3;
            if (c == 0xf0) lo = 0x90;
            if (c == 0xf4) hi = 0x8f;
        } else {
            return false;
        }
        if (i + n >= s.size()) return false;  // cut short
        for (std::size_t k = 1; k <= n; ++k) {
            const auto b = static_cast<unsigned char>(s[i + k]);
            if (k == 1 ? (b < lo || b > hi) : (b < 0x80 || b > 0xbf)) return false;
        }
        i += n + 1;
    }
    return true;
}

bool isDeviceName(std::string_view name) {
    // The part before the first dot names the device: "nul.txt" is NUL.
    const std::string stem = folderNameKey(name.substr(0, name.find('.')));
    static constexpr std::array<std::string_view, 4> kPlain = {"con", "prn", "aux", "nul"};
    for (std::string_view d : kPlain)
        if (stem == d) return true;
    return stem.size() == 4 && (stem.compare(0, 3, "com") == 0 || stem.compare(0, 3, "lpt") == 0) &&
           stem[3] >= '1' && stem[3] <= '9';
}

}  // namespace

std::string folderNameProblem(std::string_view name) {
    if (name.empty()) return "is empty";
    if (name == "." || name == "..")
        return fmt::format("is '{}', which names a folder already", name);
    if (name.size() > kMaxBytes)
        return fmt::format("is {} bytes long, more than {}", name.size(), kMaxBytes);
    if (!isUtf8(name)) return "is not valid UTF-8";
    for (const char ch : name) {
        const auto c = static_cast<unsigned char>(ch);
        if (isControl(c)) return fmt::format("contains the control character \\x{:02x}", c);
        if (ch == '/' || ch == '\\') return fmt::format("contains the path separator '{}'", ch);
        if (std::string_view("<>:\"|?*").find(ch) != std::string_view::npos)
            return fmt::format("contains '{}', which Windows refuses in a folder name", ch);
    }
    if (name.back() == '.' || name.back() == ' ')
        return "ends in a dot or a space, which Windows drops";
    if (isDeviceName(name)) return "is a device name on Windows";
    return {};
}

std::string_view folderNameRule() {
    return "a scene name names its output folder: 1 to 100 characters, none of / \\ < > : \" | "
           "? * and no control character, not '.' or '..', not ending in a dot or a space, not a "
           "Windows device name (CON, PRN, AUX, NUL, COM1-9, LPT1-9); letters, digits, spaces "
           "and - _ . + ( ) are all fine";
}

std::string folderNameKey(std::string_view name) {
    std::string key(name);
    for (char& c : key)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return key;
}

std::string printable(std::string_view text, std::size_t limit) {
    const bool utf8 = isUtf8(text);
    std::string out;
    for (std::size_t i = 0; i < text.size() && i < limit; ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (isControl(c) || (!utf8 && c >= 0x80))
            out += fmt::format("\\x{:02x}", c);
        else
            out += text[i];
    }
    if (text.size() > limit) out += "...";
    return out;
}

}  // namespace twinrender::core
