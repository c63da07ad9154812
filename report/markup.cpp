#include "report/markup.h"

#include <fmt/format.h>

#include <cctype>

namespace twinrender::report {

namespace {

// The entity of a character that markup reserves in text and quoted attributes, or nullptr.
const char* entity(char c) {
    switch (c) {
        case '&':
            return "&amp;";
        case '<':
            return "&lt;";
        case '>':
            return "&gt;";
        case '"':
            return "&quot;";
        default:
            return nullptr;
    }
}

}  // namespace

std::string htmlEscape(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        if (c == '\'')
            out += "&#39;";
        else if (const char* e = entity(c))
            out += e;
        else
            out += c;
    }
    return out;
}

std::string xmlEscape(std::string_view text, bool attribute) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '\r') continue;
        if (attribute && c == '\n')
            out += "&#10;";
        else if (attribute && c == '\t')
            out += "&#9;";
        else if (c == '"' && !attribute)
            out += c;
        else if (const char* e = entity(c))
            out += e;
        else if (u < 0x20 && c != '\n' && c != '\t')
            out += ' ';  // not allowed in XML 1.0
        else
            out += c;
    }
    return out;
}

std::string markdownEscape(std::string_view text) {
    static constexpr std::string_view SPECIAL = "\\`*_[]<>|~&$#@!";
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        if (c == '\n' || c == '\r' || c == '\t')
            out += ' ';
        else if (SPECIAL.find(c) != std::string_view::npos)
            out += std::string{'\\', c};
        else
            out += c;
    }
    return out;
}

std::string urlPath(std::string_view path) {
    std::string out;
    for (char ch : path) {
        const auto c = static_cast<unsigned char>(ch);
        if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || c == '/')
            out += ch;
        else
            out += fmt::format("%{:02X}", c);
    }
    return out;
}

std::string pathOfUrl(std::string_view url) {
    std::string out;
    for (std::size_t i = 0; i < url.size(); ++i) {
        if (url[i] == '%' && i + 2 < url.size() &&
            std::isxdigit(static_cast<unsigned char>(url[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(url[i + 2]))) {
            out += static_cast<char>(std::stoi(std::string(url.substr(i + 1, 2)), nullptr, 16));
            i += 2;
        } else {
            out += url[i];
        }
    }
    return out;
}

}  // namespace twinrender::report
